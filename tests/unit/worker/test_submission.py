"""Validation, pricing and idempotency hashing of submissions."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel, ConfigDict, Field

from worker.contract import JobContext, JobOutcome
from worker.errors import CostLimitExceeded, InvalidInputs, NoSuchProcess, QueueFull, QuotaExceeded
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.registry import default_registry
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.submission import request_hash, submit, validate_inputs


class Inner(BaseModel):
    model_config = ConfigDict(extra="forbid")
    n: int = Field(ge=1)


class Inputs(BaseModel):
    model_config = ConfigDict(extra="forbid")
    sizes: list[float]
    inner: Inner


def run(inputs: Inputs, ctx: JobContext) -> JobOutcome:
    return JobOutcome({"ok": True})


REGISTRY = ProcessRegistry(
    (
        ProcessDefinition(
            id="toy",
            title="Toy",
            description="",
            inputs_model=Inputs,
            run=run,
            examples=(),
            outputs={},
            cost=lambda i: int(sum(i.sizes)),
            cost_limit=100,
            time_limit_s=50,
        ),
    )
)


def test_field_errors_use_dotted_paths_with_indices(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    with pytest.raises(InvalidInputs) as info:
        submit(
            store,
            REGISTRY,
            WorkerSettings(),
            "toy",
            {"sizes": [1, "x"], "inner": {"n": 0}, "Extra": 1},
        )
    fields = {e["field"] for e in info.value.errors}
    assert fields == {"inputs.sizes[1]", "inputs.inner.n", "inputs.Extra"}
    assert info.value.detail.startswith("Invalid value for 'inputs.")
    assert "2 more" in info.value.detail


def test_cost_limit_is_checked_before_anything_is_stored(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    with pytest.raises(CostLimitExceeded, match="costs 101") as info:
        submit(store, REGISTRY, WorkerSettings(), "toy", {"sizes": [101], "inner": {"n": 1}})
    assert info.value.extra["cost_limit"] == 100
    assert store.list_jobs(limit=10).jobs == []


def test_unknown_process(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    with pytest.raises(NoSuchProcess, match="available: toy"):
        submit(store, REGISTRY, WorkerSettings(), "nope", {})


def test_time_limit_is_capped_by_settings(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    job, _ = submit(
        store,
        REGISTRY,
        WorkerSettings(max_time_limit_s=7),
        "toy",
        {"sizes": [1], "inner": {"n": 1}},
    )
    assert job.time_limit_s == 7
    job, _ = submit(store, REGISTRY, WorkerSettings(), "toy", {"sizes": [1], "inner": {"n": 1}})
    assert job.time_limit_s == 50


def test_a_time_limit_from_the_inputs_is_capped_by_the_process_and_settings(
    tmp_path: Path,
) -> None:
    # a process whose work grows with its inputs gives each job its own limit
    toy = REGISTRY.get("toy")
    assert toy is not None
    scaled = dataclasses.replace(toy, attempt_time_limit=lambda i: 10.0 * sum(i.sizes))
    registry = ProcessRegistry((scaled,))
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    limits = [
        submit(store, registry, settings, "toy", {"sizes": sizes, "inner": {"n": 1}})[
            0
        ].time_limit_s
        for sizes, settings in (
            ([1], WorkerSettings()),
            ([2, 1], WorkerSettings()),
            ([9], WorkerSettings()),  # 90 s asked, the process allows 50
            ([2, 1], WorkerSettings(max_time_limit_s=20)),
        )
    ]
    assert limits == [10, 30, 50, 20]


def test_request_hash_ignores_key_order_but_not_values() -> None:
    assert request_hash("p", {"a": 1, "b": 2}) == request_hash("p", {"b": 2, "a": 1})
    assert request_hash("p", {"a": 1}) != request_hash("p", {"a": 2})
    assert request_hash("p", {"a": 1}) != request_hash("q", {"a": 1})


# -- the published schema is the contract ---------------------------------------------


@pytest.mark.parametrize(
    ("process_id", "raw", "field"),
    [
        ("fourbar-grashof", {"lengths": ["30", 17, 18, 25], "ground": 0}, "inputs.lengths[0]"),
        (
            "planar3r-dexterity-map",
            {
                "links": [15, 14, 8],
                "trajectory": {
                    "x_start": 14.0,
                    "x_end": False,
                    "polynomial": [1, 2],
                    "samples": 10,
                },
            },
            "inputs.trajectory.x_end",
        ),
    ],
)
def test_lax_coercions_the_schema_does_not_publish_are_refused(
    process_id: str, raw: dict[str, Any], field: str
) -> None:
    """Pydantic would read ``"30"`` as 30 and ``true`` as 1; the schema says number."""
    definition = default_registry().get(process_id)
    assert definition is not None
    with pytest.raises(InvalidInputs) as caught:
        validate_inputs(definition, raw)
    assert [e["field"] for e in caught.value.errors] == [field], caught.value.errors
    assert "input schema" in caught.value.errors[0]["message"]


def test_every_worked_example_matches_its_published_schema() -> None:
    for definition in default_registry():
        for example in definition.examples:
            validate_inputs(definition, example.inputs)


# -- what a submission records for scheduling and retention ----------------------------


def test_cheapness_and_retention_are_recorded_at_submission(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    registry = default_registry()
    settings = WorkerSettings(result_ttl_s=3600)
    small = {"lengths": [2, 7, 9, 6], "ground": 1}
    job, _ = submit(store, registry, settings, "fourbar-grashof", small)
    big = {"links": [15, 14, 8], "grid": {"points_per_axis": 501}}
    heavy, _ = submit(store, registry, settings, "planar3r-dexterity-map", big, retention_s=60)
    row = store._one(
        store._conn(),
        "SELECT cheap, retention_s FROM jobs WHERE job_id = ?",  # type: ignore[attr-defined]
        (job.job_id,),
    )
    assert row["cheap"] == 1 and row["retention_s"] == 3600
    row = store._one(
        store._conn(),
        "SELECT cheap, retention_s FROM jobs WHERE job_id = ?",  # type: ignore[attr-defined]
        (heavy.job_id,),
    )
    assert row["cheap"] == 0 and row["retention_s"] == 60


def test_an_api_keys_submissions_meet_its_quota(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    settings = WorkerSettings(max_queued_per_key=2, max_queued=3)
    inputs = {"sizes": [1], "inner": {"n": 1}}
    for _ in range(2):
        submit(store, REGISTRY, settings, "toy", inputs, owner="alice")
    with pytest.raises(QuotaExceeded):
        submit(store, REGISTRY, settings, "toy", inputs, owner="alice")
    submit(store, REGISTRY, settings, "toy", inputs)  # anonymous: only the whole queue
    with pytest.raises(QueueFull):
        submit(store, REGISTRY, settings, "toy", inputs)
