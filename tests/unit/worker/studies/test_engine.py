"""Which engine a study takes, what it costs, how it is chunked, and how objectives are
read from a kernel's arrays (as from a result document)."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY, chunk_inputs, dry_check, study_cost
from worker.registry import default_registry
from worker.studies import chunking
from worker.studies.batched import objective_column
from worker.studies.engine import choose_engine, pattern_matches
from worker.studies.examples import STUDY_EXAMPLES
from worker.studies.paths import parse_result_path, read_result
from worker.studies.spec import StudySpec

REGISTRY = default_registry()
SPM = dict(STUDY_EXAMPLES[0].inputs)
ARM = dict(STUDY_EXAMPLES[3].inputs)
#: A study of a process without a kernel.
UNBATCHED = dict(STUDY_EXAMPLES[1].inputs)


def choice_of(inputs: dict[str, Any]) -> Any:
    spec = StudySpec.model_validate(inputs)
    process = REGISTRY.get(spec.process)
    assert process is not None
    return choose_engine(spec, process)


def test_a_study_is_batched_when_its_kernel_covers_it() -> None:
    assert choice_of(SPM).engine == "batched"
    assert choice_of({**SPM, "engine": "per-design"}).why == (
        "the study asks for the per-design engine"
    )
    assert choice_of(ARM).engine == "batched"
    plain = choice_of(UNBATCHED)
    assert plain.engine == "per-design" and "has no study kernel" in plain.why
    region = choice_of({**ARM, "objectives": {"regions[].d_z_min|min": "max"}})
    assert "does not cover the objective 'regions[].d_z_min|min'" in region.why
    limits = choice_of({**ARM, "vary": {"joint_limits_deg[0][1]": [90, 180, 3]}})
    assert "cannot vary 'joint_limits_deg[0][1]'" in limits.why
    uncovered = choice_of({**SPM, "objectives": {"type_ii_singularity.min_abs_det_a": "max"}})
    assert "does not cover the objective 'type_ii_singularity.min_abs_det_a'" in uncovered.why
    tilt = choice_of({**SPM, "fixed": {"beta_deg": 90, "gamma_deg": 0},
                      "vary": {"alpha1_deg": [40, 90, 3],
                               "workspace.tilt_max_deg": [30, 60, 2]}})  # fmt: skip
    assert "cannot vary 'workspace.tilt_max_deg'" in tilt.why


def test_asking_for_a_batched_study_that_cannot_be_is_a_422_at_engine() -> None:
    problems = dry_check(StudySpec.model_validate({**UNBATCHED, "engine": "batched"}))
    assert [p["field"] for p in problems] == ["inputs.engine"]
    assert (
        "cannot be batched: planar2dof-optimisation has no study kernel" in (problems[0]["message"])
    )
    assert dry_check(StudySpec.model_validate({**SPM, "engine": "batched"})) == []


def test_an_index_past_a_covered_list_is_refused_on_the_kernels_answer() -> None:
    chains = dict(STUDY_EXAMPLES[2].inputs)
    problems = dry_check(StudySpec.model_validate(
        {**chains, "objectives": {"chains[7].P": "max", "chains[4].Q": "min"}}))  # fmt: skip
    assert [p["field"] for p in problems] == ["inputs.objectives.chains[7].P"]


def test_a_million_designs_of_indices_are_accepted_with_the_default_limits() -> None:
    """Example I's workspace at its sampling (144 orientations), 10^6 designs starting at
    one that reaches it: 288 jobs' worth through the kernel, where a job per design
    priced it at 77,150 (above the 1,000 allowed)."""
    million = {**SPM, "vary": {"alpha1_deg": [60, 150, 1000], "alpha2_deg": [90, 150, 1000]}}
    spec = StudySpec.model_validate(million)
    assert study_cost(spec) == 288 * 1_000_000 <= STUDY.cost_limit
    per_design = StudySpec.model_validate({**million, "engine": "per-design"})
    assert study_cost(per_design) > STUDY.cost_limit


def test_the_kernels_price_follows_the_objectives() -> None:
    def cost(objectives: dict[str, str]) -> float:
        plan = choice_of({**SPM, "objectives": objectives}).plan
        return float(plan.cost)

    assert cost({"indices.gci": "max"}) == 144
    assert cost({"workspace_minimum.inverse_condition": "max"}) == 144 + 22_464
    assert cost({"indices.real_samples": "max"}) == 144 + 236_880


def _no_clock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Any reading of a clock while the chunks are planned fails the test."""

    def never(*args: Any, **kwargs: Any) -> Any:
        raise AssertionError("a study's chunks are planned without timing anything")

    # not time.time: imports (numpy.f2py) and logging read the wall clock, not a timer
    for name in ("perf_counter", "perf_counter_ns", "monotonic", "monotonic_ns",
                 "process_time", "process_time_ns"):  # fmt: skip
        monkeypatch.setattr(time, name, never)


def test_batched_chunks_follow_the_cost_model_alone(monkeypatch: pytest.MonkeyPatch) -> None:
    """No design is timed: the same inputs give the same chunks, sized for about a
    second by the kernel's cost and throughput."""

    _no_clock(monkeypatch)
    inputs = {**SPM, "vary": {"alpha1_deg": [30, 150, 500], "alpha2_deg": [30, 150, 400]}}
    spec = StudySpec.model_validate(inputs)
    first, again = chunk_inputs(spec), chunk_inputs(spec)
    assert [(c["start"], c["stop"]) for c in first] == [(c["start"], c["stop"]) for c in again]
    choice = choice_of(inputs)
    size = math.ceil(1.0 / chunking.design_seconds(choice))
    assert first[0]["stop"] == size and {c["engine"] for c in first} == {"batched"}
    assert first[-1]["stop"] == 200_000 and len(first) == math.ceil(200_000 / size)


def test_per_design_chunks_follow_the_cost_model_alone(monkeypatch: pytest.MonkeyPatch) -> None:
    """A per-design study times no design either: its chunks follow from a job's cost
    model on the first design the process accepts (the first designs of this study are
    refused: they reach none of the workspace), so a re-run splits the same way on any
    machine; ``chunk_size`` still overrides."""
    inputs = {**SPM, "engine": "per-design"}
    spec = StudySpec.model_validate(inputs)
    process = REGISTRY.get(spec.process)
    assert process is not None
    with monkeypatch.context() as patched:
        _no_clock(patched)
        first, again = chunk_inputs(spec), chunk_inputs(spec)
        seconds = chunking.per_design_seconds(spec, process)
        given_size = chunk_inputs(StudySpec.model_validate({**inputs, "chunk_size": 7}))
    bounds = [(c["start"], c["stop"]) for c in first]
    assert bounds == [(c["start"], c["stop"]) for c in again]
    assert {c["engine"] for c in first} == {"per-design"}
    expected = min(math.ceil(1.0 / seconds), math.ceil(spec.designs.count / chunking.MIN_CHUNKS))
    assert bounds[0] == (0, expected) and bounds[-1][1] == spec.designs.count
    cost = 38_575  # the accepted designs' cost (16 orientations over the workspace)
    assert seconds == pytest.approx(
        process.seconds_per_run + cost * process.seconds_per_cost
        + chunking.VALIDATION_SECONDS_PER_DESIGN
    )  # fmt: skip
    assert [c["stop"] - c["start"] for c in given_size[:-1]] == [7] * (len(given_size) - 1)


def test_a_study_says_which_engine_ran_it() -> None:
    small = {**SPM, "vary": {"alpha1_deg": [45, 135, 4], "alpha2_deg": [60, 120, 3]},
             "plots": False}  # fmt: skip
    batched = STUDY.run(StudySpec.model_validate(small), RecordingContext()).result
    assert (batched["engine"], batched["engine_reason"]) == ("batched", "")
    slow = STUDY.run(StudySpec.model_validate({**small, "engine": "per-design"}),
                     RecordingContext()).result  # fmt: skip
    assert slow["engine"] == "per-design" and "asks for" in slow["engine_reason"]
    assert batched["best"] == slow["best"] and batched["pareto"] == slow["pareto"]


def test_input_patterns() -> None:
    assert pattern_matches("chains[].lengths[]", ("chains", 3, "lengths", 2))
    assert pattern_matches("chains[].links.*", ("chains", 0, "links", "a"))
    assert not pattern_matches("chains[].links.*", ("chains", 0, "links", 1))
    assert not pattern_matches("links[]", ("links",))
    assert not pattern_matches("alpha1_deg", ("alpha2_deg",))


@st.composite
def arrays_and_paths(draw: st.DrawFn) -> tuple[np.ndarray, str, str]:
    """A kernel's array for a declared path with one or two lists, and an objective
    reading it (indices, maybe past the end, and reductions)."""
    depth = draw(st.integers(0, 2))
    shape = tuple(draw(st.integers(0, 3)) for _ in range(depth))
    values = st.one_of(st.floats(-1e6, 1e6), st.just(np.nan), st.just(np.inf),
                       st.integers(-3, 3).map(float))  # fmt: skip
    array = np.array(draw(st.lists(values, min_size=int(np.prod(shape)) * 2,
                                   max_size=int(np.prod(shape)) * 2)),
                     dtype=np.float64).reshape((2, *shape))  # fmt: skip
    declared = "a" + "".join(f".b{k}[]" for k in range(depth)) + ".c"
    steps = ["a"] + [f"b{k}[{draw(st.sampled_from(['', '0', '1', '5']))}]" for k in range(depth)]
    text = ".".join(steps) + ".c"
    if "[]" in text or draw(st.booleans()):
        text += "|" + draw(st.sampled_from(["min", "max", "mean", "sum"]))
    return array, declared, text


def document(values: np.ndarray, depth: int) -> Any:
    """The result document a kernel's row stands for: NaN as null (as JSON has it)."""

    def build(node: Any, level: int) -> Any:
        if level == depth:
            return {"c": None if math.isnan(node) else float(node)}
        return {f"b{level}": [build(child, level + 1) for child in node]}

    return {"a": build(values, 0)}


@settings(max_examples=300, deadline=None, derandomize=True)
@given(arrays_and_paths())
def test_objectives_are_read_as_from_a_result_document(case: tuple[np.ndarray, str, str]) -> None:
    array, declared, text = case
    path = parse_result_path(text)
    depth = declared.count("[]")
    column = objective_column(array, declared, path)
    for row in range(2):
        expected = read_result(document(array[row], depth), path)
        got = None if math.isnan(column[row]) else float(column[row])
        assert got == expected, (text, array[row], got, expected)
