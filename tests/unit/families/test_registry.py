"""What every family owes the runtime, checked over the registry (as scikit-learn's
``test_common`` checks every estimator): a family lists its processes in ``PROCESSES``,
says who it is in ``FAMILY`` and exports nothing else; every process has a unique ID, a
method page, declared files, worked examples that validate and fit the cost limit, and a
description that serialises; ``run`` is a lazy shim of the family's package."""

from __future__ import annotations

import importlib
import json
from pathlib import Path

import pytest

from worker.processes import ProcessDefinition
from worker.registry import default_registry

ROOT = Path(__file__).resolve().parents[3]
FAMILIES = sorted(p.parent.name for p in (ROOT / "worker/families").glob("*/__init__.py"))
DEFINITIONS = list(default_registry())


@pytest.mark.parametrize("family", FAMILIES)
def test_a_family_exports_its_processes_and_nothing_else(family: str) -> None:
    package = importlib.import_module(f"worker.families.{family}")
    assert package.PROCESSES, family
    names = set(package.__all__)
    assert {"PROCESSES", "FAMILY"} <= names
    assert package.FAMILY.name == family
    exported = sorted(getattr(package, n).id for n in names - {"PROCESSES", "FAMILY"})
    assert exported == sorted(d.id for d in package.PROCESSES), family
    for definition in package.PROCESSES:
        assert definition.run.__module__ == f"worker.families.{family}", definition.id


def test_the_registry_holds_every_familys_processes_in_family_order() -> None:
    order = ("planar_serial", "planar_parallel", "chains", "spherical_parallel", "serial")
    expected = [
        d.id
        for family in order
        for d in importlib.import_module(f"worker.families.{family}").PROCESSES
    ]
    # then the processes built on the families (worker/studies)
    assert [d.id for d in DEFINITIONS] == [*expected, "design-study"]
    assert sorted(order) == FAMILIES


@pytest.mark.parametrize("definition", DEFINITIONS, ids=lambda d: d.id)
def test_every_process_keeps_the_contract(definition: ProcessDefinition) -> None:
    assert definition.title and definition.description and definition.outputs
    assert definition.method_doc, definition.id
    assert (ROOT / "docs/methods" / f"{definition.method_doc}.md").is_file()
    assert definition.files, f"{definition.id} declares no files"
    assert 0 <= definition.sync_cost_limit <= definition.cost_limit
    if definition.preview is not None:  # a preview costs no more than a synchronous answer
        assert definition.preview.cost_limit <= definition.sync_cost_limit
    assert definition.time_limit_s > 0
    json.dumps(definition.describe())
    json.dumps(definition.summary())
    assert definition.examples, f"{definition.id} has no worked example"
    for example in definition.examples:
        spec = definition.inputs_model.model_validate(dict(example.inputs))
        cost = definition.cost(spec)
        assert 0 < cost <= definition.cost_limit, (definition.id, example.title, cost)
