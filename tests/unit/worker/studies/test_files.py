"""A study's data files name every column with its unit: a varied input's from the
input schema, an objective's from the result path the process declares (a reduction
keeps it; a length in the fixed length_unit), never ``[as reported]``."""

from __future__ import annotations

import csv
import io
import json
from typing import Any

import numpy as np

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY
from worker.registry import default_registry
from worker.studies.files import objective_entry, objective_unit
from worker.studies.spec import StudySpec

REGISTRY = default_registry()
ARM: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "task_points": [[14, 14], [12, 8]],
              "grid": {"points_per_axis": 5}, "length_unit": "cm"},
    "vary": {"links[0]": [12, 16, 2], "links[2]": [6, 8, 2]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min",
                   "areas.reachable": "max"},
    "plots": False,
}  # fmt: skip


def files(inputs: dict[str, Any]) -> dict[str, bytes]:
    outcome = STUDY.run(StudySpec.model_validate(inputs), RecordingContext())
    return {a.name: a.data for a in outcome.artifacts}


def test_objective_columns_carry_the_declared_units() -> None:
    data = files(ARM)
    header = next(csv.reader(io.StringIO(data["designs.csv"].decode())))
    assert header == ["index [-]", "links_0 [cm]", "links_2 [cm]", "task_points_d_z_min [-]",
                      "links_sum [cm]", "areas_reachable [cm^2]", "feasible [-]",
                      "reason_code [-]"]  # fmt: skip
    with np.load(io.BytesIO(data["designs.npz"])) as npz:
        assert npz["objective_units"].tolist() == ["-", "cm", "cm^2"]
        assert npz["objective_symbols"].tolist() == ["$d_z$", "$l_i$", ""]
        assert json.loads(str(npz["units"]))["objectives"] == "objective_units"


def test_an_objective_reads_the_declaration_of_its_path() -> None:
    arm = REGISTRY.get("planar3r-dexterity-map")
    chains = REGISTRY.get("chain-parallelism")
    five_bar = REGISTRY.get("planar2dof-optimisation")
    assert arm is not None and chains is not None and five_bar is not None
    for process, path, declared in [
        (arm, "task_points[3].d_z", "task_points[].d_z"),
        (arm, "full_dexterity_bands[]|max", "full_dexterity_bands[][]"),
        (chains, "chains[3].rank.by_Q", "chains[].rank.by_Q"),
        (five_bar, "optimum.S", "optimum.S"),
    ]:
        entry = objective_entry(process, path)
        assert entry is not None and entry.path == declared, path
    assert objective_entry(arm, "method") is None
    assert objective_unit(chains, "chains[0].Q", {"length_unit": "mm"}) == "mm^4"
    assert objective_unit(chains, "chains[0].Q_normalized", {}) == "-"
    assert objective_unit(five_bar, "optimum.S", {}) == "l1^2"
    assert objective_unit(arm, "links|sum", {}) == "units"  # the process's default unit
