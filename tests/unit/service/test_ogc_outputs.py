"""The outputs the OGC descriptions list are what jobs produce: every result member and
every file, in its media type (each process run once, on a small problem, plots on)."""

from __future__ import annotations

from typing import Any

import pytest

from service.ogc.outputs import process_outputs
from worker.registry import default_registry
from worker.submission import validate_inputs

pytestmark = pytest.mark.slow

_SAMPLES = {"azimuth": 4, "tilt": 3, "torsion": 3}

#: Small problems that write every file their process can write.
SMALL: dict[str, dict[str, Any] | None] = {
    "planar3r-dexterity-map": {
        "links": [15, 14, 8],
        "task_points": [[14, 14]],
        "grid": {"points_per_axis": 15},
        "trajectory": {"polynomial": [1.0, 0.0], "x_start": 1.0, "x_end": 5.0, "samples": 10},
    },
    "planar3r-synthesis": {
        "task_points": [[16.0, 19.0], [18.0, 0.0], [-8.0, -25.0]],
        "l3": 15.0,
        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "grid": {"points_per_axis": 15},
        "orientation_step_deg": 10,
    },
    "planar3r-design": {
        "task_points": [[14.0, 14.0], [8.0, -8.0]],
        "trajectory": {"points": [[14.0, 14.0], [8.0, -8.0]], "samples": 5},
        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "total_length_max": 37.0,
        "max_generations": 3,
        "grid": {"points_per_axis": 15},
    },
    "design-study": {
        "process": "planar3r-dexterity-map",
        "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
        "vary": {"links[0]": [10, 20, 3], "links[2]": [6, 8, 2]},
        "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    },
    "planar2dof-conditioning-map": {
        "l2": 1.5,
        "architecture": "isotropic",
        "inverse_condition_limit": 0.5,
        "grid": {"points_per_axis": 31},
    },
    "planar2dof-optimisation": {
        "allowable_pressure_angle_deg": 30.0,
        "aspect_ratio": 4.0,
        "delta_range": [1.5, 2.0],
        "delta_step": 0.25,
        "mean_mesh": 5,
    },
    "chain-parallelism": None,  # the first worked example
    "fourbar-grashof": None,
    "serial-indices": None,
    "serial-reach": None,
    "spm-conditioning-map": {
        "alpha1_deg": 60.0,
        "alpha2_deg": 90.0,
        "beta_deg": 90.0,
        "gamma_deg": 0.0,
        "workspace": {"tilt_max_deg": 60.0, "torsion_deg": [0.0, 360.0], "samples": _SAMPLES},
    },
    "spm-design-space": {
        "workspace": {"tilt_max_deg": 60.0, "torsion_deg": [0.0, 360.0], "samples": _SAMPLES},
        "gamma_deg": 0.0,
        "beta_deg": [75.0, 90.0],
        "index_map": {"beta_deg": 75.0, "points_per_side": 5},
    },
    "spm-optimisation": {
        "workspace": {"tilt_max_deg": 45.0, "torsion_deg": [-15.0, 15.0], "samples": _SAMPLES},
        "identical_platforms": True,
        "free": ["alpha1", "alpha2"],
        "beta_deg": 33.3,
        "starts": 2,
        "max_evaluations_per_start": 20,
    },
}


class _Quiet:
    def report_progress(self, percent: float, message: str = "") -> None:
        pass


def test_every_registered_process_has_its_files_listed() -> None:
    assert set(SMALL) == {d.id for d in default_registry()}
    assert all(d.files for d in default_registry())


@pytest.mark.parametrize("process_id", sorted(SMALL))
def test_declared_outputs_match_a_real_run(process_id: str) -> None:
    definition = default_registry().get(process_id)
    assert definition is not None
    raw = SMALL[process_id] or dict(definition.examples[0].inputs)
    outcome = definition.run(validate_inputs(definition, raw), _Quiet())
    outputs = process_outputs(definition)
    files = {a.name: a.media_type for a in outcome.artifacts}
    declared = {o.id: o.media_type for o in outputs.values() if o.artifact}
    assert files == declared
    members = {o.id for o in outputs.values() if not o.artifact}
    assert set(outcome.result) | {"notes"} <= members
    for spec in outputs.values():
        description = spec.describe()
        assert description["title"] and description["description"]
        if spec.artifact:
            assert description["schema"]["contentMediaType"] == spec.media_type
