"""The paper's errata are marked in results: for each family a worked example whose paper
prints something wrong gets the correction in ``notes`` and again in ``paper_errata``; a
request that is not the paper's gets ``paper_errata == []``.

Each request runs through the real worker loop (claim, run, commit) on a SQLite store
with the default registry, so the result document is the one a client reads.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from worker.contract import JobStatus
from worker.families.planar_serial.examples import EXAMPLE_2_LABELS, EXAMPLE_2_TASK_POINTS
from worker.registry import default_registry
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import JobStore, NewJob

SMALL_GRID = {"points_per_axis": 21}
EXAMPLE_1_SPM = {"tilt_max_deg": 60.0, "torsion_deg": [0.0, 360.0]}
SMALL_MAPS = {"map_grid": {"azimuth": 5, "tilt": 2}, "plots": False}

#: (process, inputs, a phrase of one expected erratum); all quick, plots off.
PAPER_REQUESTS = [
    pytest.param(
        "planar3r-dexterity-map",
        {"links": [15.0, 8.0, 14.0], "grid": SMALL_GRID, "plots": False},
        "the paper gives the high-dexterity band of the arm with l2 and l3 swapped as 8 < d <= 16",
        id="planar3r-example-1-case-2",
    ),
    pytest.param(
        "planar3r-synthesis",
        {
            "task_points": [list(p) for p in EXAMPLE_2_TASK_POINTS],
            "task_labels": list(EXAMPLE_2_LABELS),
            "l3": 15.0,
            "grid": SMALL_GRID,
            "plots": False,
        },
        "'29 (Point F) and 18 (Point B)'; they are swapped",
        id="planar3r-example-2",
    ),
    pytest.param(
        "planar2dof-conditioning-map",
        {"l2": 1.85, "architecture": "isotropic", "grid": SMALL_GRID, "plots": False},
        "Table I prints e = 0.6001 for delta = 1.85",
        id="planar2dof-table-i-35",
    ),
    pytest.param(
        "spm-conditioning-map",
        {
            "alpha1_deg": 60.0,
            "alpha2_deg": 90.0,
            "beta_deg": 90.0,
            "workspace": EXAMPLE_1_SPM,
            **SMALL_MAPS,
        },
        "Table 1 prints 'C_n' = 0.28",
        id="spm-table-1",
    ),
    pytest.param(
        "chain-parallelism",
        {"chains": [{"name": "2d", "lengths": [18.0, 15.0, 10.0, 17.0]}], "plots": False},
        "it prints the deviations as 36, 120, 20, 126",
        id="chains-fig-2d",
    ),
]

#: The same processes on requests that are not the paper's examples.
OTHER_REQUESTS = [
    pytest.param(
        "planar3r-dexterity-map",
        {"links": [1.0, 1.0, 1.0], "grid": SMALL_GRID, "plots": False},
        id="planar3r",
    ),
    pytest.param(
        "planar3r-synthesis",
        {"task_points": [[3.0, 4.0], [6.0, 0.0]], "l3": 2.0, "grid": SMALL_GRID, "plots": False},
        id="planar3r-synthesis",
    ),
    pytest.param(
        "planar2dof-conditioning-map",
        {"l2": 1.5, "architecture": "isotropic", "grid": SMALL_GRID, "plots": False},
        id="planar2dof",
    ),
    pytest.param(
        "spm-conditioning-map",
        {
            "alpha1_deg": 60.0,
            "alpha2_deg": 90.0,
            "beta_deg": 90.0,
            "workspace": {"tilt_max_deg": 50.0},
            **SMALL_MAPS,
        },
        id="spm",
    ),
    pytest.param(
        "chain-parallelism",
        {"chains": [{"name": "q", "lengths": [1.0, 2.0, 3.0, 4.0]}], "plots": False},
        id="chains",
    ),
]


@pytest.fixture
def store(tmp_path: Path) -> JobStore:
    return open_store(f"sqlite:///{tmp_path / 'jobs.db'}")


def run_through_the_worker(store: JobStore, process_id: str, inputs: dict[str, Any]) -> Any:
    job, _ = store.create_job(NewJob(process_id, inputs, time_limit_s=120, max_attempts=1))
    loop = WorkerLoop(WorkerSettings(workers=1), store, default_registry())
    claim = store.claim_next(loop.worker_id, 30)
    assert claim is not None
    loop.execute(claim)
    record = store.get_job(job.job_id)
    assert record is not None and record.status is JobStatus.SUCCESSFUL, record
    return store.get_result(job.job_id)


def run_directly(process_id: str, inputs: dict[str, Any]) -> Any:
    definition = default_registry().get(process_id)
    assert definition is not None
    return definition.run(definition.inputs_model.model_validate(inputs), _Silent())


class _Silent:
    def report_progress(self, percent: float, message: str = "") -> None:
        pass


@pytest.mark.parametrize(("process_id", "inputs", "phrase"), PAPER_REQUESTS)
def test_a_paper_example_has_its_errata_in_notes_and_in_paper_errata(
    store: JobStore, process_id: str, inputs: dict[str, Any], phrase: str
) -> None:
    result = run_through_the_worker(store, process_id, inputs)
    errata, notes = result["paper_errata"], result["notes"]
    assert any(phrase in erratum for erratum in errata), errata
    # notes keep every note, the errata last and in the same order
    assert notes[len(notes) - len(errata) :] == errata
    assert len(set(notes)) == len(notes)


@pytest.mark.parametrize(("process_id", "inputs", "phrase"), PAPER_REQUESTS)
def test_a_job_returns_the_errata_apart_from_its_other_notes(
    process_id: str, inputs: dict[str, Any], phrase: str
) -> None:
    outcome = run_directly(process_id, inputs)
    assert any(phrase in erratum for erratum in outcome.errata)
    assert not any(phrase in note for note in outcome.notes)
    assert outcome.all_notes == (*outcome.notes, *outcome.errata)


@pytest.mark.parametrize(("process_id", "inputs"), OTHER_REQUESTS)
def test_a_request_that_is_not_the_papers_has_no_paper_errata(
    store: JobStore, process_id: str, inputs: dict[str, Any]
) -> None:
    result = run_through_the_worker(store, process_id, inputs)
    assert result["paper_errata"] == []
    assert isinstance(result["notes"], list)


def test_what_confirms_the_paper_is_a_note_not_an_erratum() -> None:
    """Fig 2e vs 2d: the paper's conclusion holds, so it is a plain note; Fig 2d's
    misprinted Q is an erratum.  Fig. 5's degenerate beta = 60 is reproduced: a note."""
    chains = run_directly(
        "chain-parallelism",
        {
            "chains": [
                {"name": "2d", "lengths": [18.0, 15.0, 10.0, 17.0]},
                {"name": "2e", "lengths": [18.0, 10.0, 17.0, 15.0]},
            ],
            "plots": False,
        },
    )
    holds = [n for n in chains.all_notes if "Fig 2e is more parallel than Fig 2d' holds" in n]
    assert holds and holds[0] in chains.notes and holds[0] not in chains.errata
    assert any("2d" in erratum or "Fig 2" in erratum for erratum in chains.errata)
    from worker.families.spherical_parallel.examples import DESIGN_SPACE_EXAMPLES

    example = next(ex for ex in DESIGN_SPACE_EXAMPLES if "60" in str(ex.inputs))
    space = run_directly("spm-design-space", {**example.inputs, "plots": False})
    assert any("as the paper says" in note for note in space.notes)
    assert space.errata == ()
