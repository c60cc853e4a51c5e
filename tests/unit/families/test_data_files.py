"""Every data file describes itself (docs/data-files.md), for every process that writes
one: a CSV's first line is its header and every column carries its unit; an NPZ holds
``axes``, ``units`` and ``metadata`` (JSON) describing every array it holds, each axis
name either an axis vector of matching length or a named count, and the job's inputs."""

from __future__ import annotations

import csv
import io
import json
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.contract import JobOutcome
from worker.registry import default_registry

#: Small inputs of every process that writes data files (plots off: only the files).
SMALL: dict[str, dict[str, Any]] = {
    "planar3r-dexterity-map": {"links": [3, 2, 1], "grid": {"points_per_axis": 21},
                               "length_unit": "mm"},
    "planar3r-synthesis": {"task_points": [[10, 0], [15, 5]], "l3": 5,
                           "grid": {"points_per_axis": 21}, "length_unit": "cm"},
    "planar3r-design": {"task_points": [[10, 0], [15, 5]], "total_length_max": 30,
                        "trajectory": {"points": [[10, 0], [15, 5]], "samples": 5},
                        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
                        "max_generations": 5, "grid": {"points_per_axis": 21},
                        "length_unit": "cm"},
    "design-study": {"process": "planar3r-dexterity-map",
                     "fixed": {"links": [3, 2, 1], "task_points": [[2, 2]],
                               "grid": {"points_per_axis": 3}},
                     "vary": {"links[0]": [2, 4, 3], "links[2]": [0.5, 1, 2]},
                     "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"}},
    "planar2dof-conditioning-map": {"l1": 1, "l2": 1.5, "architecture": "isotropic",
                                    "inverse_condition_limit": 0.5,
                                    "grid": {"points_per_axis": 31}, "length_unit": "m"},
    "planar2dof-optimisation": {"allowable_pressure_angle_deg": 30,
                                "delta": 1.5, "mean_mesh": 11},
    "spm-conditioning-map": {"alpha1_deg": 60, "alpha2_deg": 90, "beta_deg": 90,
                             "workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
                             "map_grid": {"azimuth": 7, "tilt": 3}},
    "spm-design-space": {"workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
                         "beta_deg": {"start": 60, "stop": 90, "step": 15}},
    "spm-optimisation": {"workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
                         "starts": 1, "max_evaluations_per_start": 20},
    "serial-workspace-map": {"robot": {"dh": [{"a": 1.0}, {"a": 1.0}]}, "samples": 2000,
                             "voxel_size": 0.5, "orientation_bins": 8, "length_unit": "m"},
}  # fmt: skip
COLUMN = re.compile(r"^[A-Za-z][A-Za-z0-9_]* \[[^\[\],]+\]$")
DEFINITIONS = {d.id: d for d in default_registry()}


def test_every_process_that_writes_data_is_covered() -> None:
    writers = {
        d.id
        for d in DEFINITIONS.values()
        if any(f.name.endswith((".csv", ".npz")) for f in d.files)
    }
    assert writers == set(SMALL)


def run(process_id: str) -> tuple[JobOutcome, dict[str, Any]]:
    definition = DEFINITIONS[process_id]
    spec = definition.inputs_model.model_validate({**SMALL[process_id], "plots": False})
    return definition.run(spec, RecordingContext()), spec.model_dump(mode="json")


@pytest.mark.parametrize("process_id", sorted(SMALL))
def test_the_data_files_describe_themselves(process_id: str) -> None:
    outcome, inputs = run(process_id)
    files = {a.name: a.data for a in outcome.artifacts}
    assert files and all(n.endswith((".csv", ".npz")) for n in files), sorted(files)
    unit = inputs.get("length_unit")
    for name, data in files.items():
        if name.endswith(".csv"):
            header = next(csv.reader(io.StringIO(data.decode())))
            assert all(COLUMN.match(c) for c in header), (name, header)
            assert len(set(header)) == len(header)
            if unit is not None:
                assert f"x [{unit}]" in header or not any(c.startswith("x [") for c in header)
            continue
        with np.load(io.BytesIO(data)) as npz:
            axes = json.loads(str(npz["axes"]))
            units = json.loads(str(npz["units"]))
            meta = json.loads(str(npz["metadata"]))
            arrays = set(npz.files) - {"axes", "units", "metadata"}
            assert set(units) == arrays, (name, sorted(arrays ^ set(units)))
            assert set(axes) <= arrays
            for array, dims in axes.items():
                shape = npz[array].shape
                assert len(dims) == len(shape), (array, dims, shape)
                for dim, size in zip(dims, shape, strict=True):
                    if dim in arrays:
                        assert npz[dim].shape == (size,), (array, dim)
            assert meta["process"] == process_id and meta["inputs"] == inputs
            assert meta["software"].startswith("dexlab ")
            if unit is not None:
                assert unit in units.values()


DOC = (Path(__file__).resolve().parents[3] / "docs" / "data-files.md").read_text()


def documented(name: str, unit: str | None) -> str:
    return name.replace(f"[{unit}]", "[<length_unit>]") if unit else name


@pytest.mark.parametrize("process_id", sorted(SMALL))
def test_docs_data_files_lists_every_column_and_array(process_id: str) -> None:
    outcome, inputs = run(process_id)
    unit = inputs.get("length_unit")
    section = DOC.split(f"## {process_id}\n", 1)[1].split("\n## ", 1)[0]
    for artifact in outcome.artifacts:
        assert f"`{artifact.name}`" in section, artifact.name
        if artifact.name.endswith(".csv"):
            header = next(csv.reader(io.StringIO(artifact.data.decode())))
            missing = [c for c in header if f"`{documented(c, unit)}`" not in section]
        else:
            with np.load(io.BytesIO(artifact.data)) as npz:
                names = set(npz.files) - {"axes", "units", "metadata"}
            missing = [n for n in names if n not in section]
        assert not missing, (process_id, artifact.name, missing)


def test_docs_data_files_lists_every_declared_file() -> None:
    for definition in DEFINITIONS.values():
        for file in definition.files:
            stem = file.name.rpartition(".")[0]
            assert f"`{file.name}`" in DOC or f"`{stem}.png`/`.svg`" in DOC, file.name
