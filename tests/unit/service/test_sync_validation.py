"""A synchronous request (``Prefer: wait``) validates and prices its inputs once in the
API: the submission's validation and cost say whether it may be answered at once."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest

from tests.unit.service.test_design_study_requests import app_client
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.registry import default_registry


def _counted(
    process_id: str, calls: dict[str, int], monkeypatch: pytest.MonkeyPatch
) -> ProcessDefinition:
    """``process_id``'s definition with its model's ``model_validate`` and its ``cost``
    counting their calls in ``calls``."""
    definition = default_registry().get(process_id)
    assert definition is not None and definition.sync_cost_limit > 0
    model = definition.inputs_model
    validate = model.model_validate

    def counted_validate(cls: Any, *args: Any, **kwargs: Any) -> Any:
        calls["validate"] += 1
        return validate(*args, **kwargs)

    def counted_cost(inputs: Any) -> int:
        calls["cost"] += 1
        return definition.cost(inputs)

    monkeypatch.setattr(model, "model_validate", classmethod(counted_validate))
    return dataclasses.replace(definition, cost=counted_cost)


@pytest.mark.parametrize(
    ("url", "prefer"),
    [("/v1/processes/fourbar-grashof/execution", "wait=1"),
     ("/ogc/processes/fourbar-grashof/execution", "respond-sync"),
     ("/ogc/processes/fourbar-grashof/execution", "wait=1")],
)  # fmt: skip
def test_a_synchronous_request_validates_and_prices_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, url: str, prefer: str
) -> None:
    calls = {"validate": 0, "cost": 0}
    definition = _counted("fourbar-grashof", calls, monkeypatch)
    inputs = dict(definition.examples[0].inputs)
    with app_client(tmp_path, ProcessRegistry([definition])) as send:
        response = send("POST", url, json={"inputs": inputs}, headers={"Prefer": prefer})
    assert response.status_code in (200, 201), response.text  # no worker: 201 after the wait
    assert calls == {"validate": 1, "cost": 1}
