"""The ``serial-indices`` job on its worked examples: the planar arm's numbers in closed
form, a singular pose, limits and the characteristic length."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.registry import default_registry
from worker.submission import validate_inputs

PROCESS = default_registry().get("serial-indices")


def run(inputs: dict[str, Any]) -> Any:
    assert PROCESS is not None
    return PROCESS.run(validate_inputs(PROCESS, {**inputs, "plots": False}), RecordingContext())


def example(title_start: str) -> dict[str, Any]:
    assert PROCESS is not None
    return dict(next(e for e in PROCESS.examples if e.title.startswith(title_start)).inputs)


def test_the_planar_arm_has_the_3r_closed_form() -> None:
    """Patel & Sobh's Example 1 arm: (x, y, φ) of the joint angles and det J = l1 l2 sin θ2."""
    l1, l2, l3 = 15.0, 14.0, 8.0
    result = run(example("Patel")).result
    assert result["arm"]["planar"] and result["arm"]["task_space"] == ["x", "y", "phi"]
    for pose in result["poses"]:
        t1, t2, t3 = (math.radians(v) for v in pose["configuration"])
        x = l1 * math.cos(t1) + l2 * math.cos(t1 + t2) + l3 * math.cos(t1 + t2 + t3)
        y = l1 * math.sin(t1) + l2 * math.sin(t1 + t2) + l3 * math.sin(t1 + t2 + t3)
        assert pose["position"][:2] == pytest.approx([x, y], abs=1e-12)
        assert pose["phi_deg"] == pytest.approx(math.degrees(t1 + t2 + t3), abs=1e-9)
        jac = np.asarray(pose["jacobian"])
        assert jac.shape == (3, 3)
        det = abs(l1 * l2 * math.sin(t2))
        assert pose["manipulability"] == pytest.approx(det, rel=1e-12)


def test_a_stretched_ur5_is_singular_and_limits_are_reported() -> None:
    result = run(example("UR5 (standard")).result
    stretched = result["poses"][2]
    assert stretched["inverse_condition"] < 1e-12 and stretched["manipulability"] < 1e-12
    assert result["poses"][0]["inverse_condition"] > 0.01
    assert all(p["within_limits"] for p in result["poses"])
    outside = run({**example("UR5 (standard"), "configurations": [[200, 0, 0, 0, 0, 0]]})
    assert outside.result["summary"]["outside_limits"] == 1
    assert outside.result["poses"][0]["limit_distance"][0] == pytest.approx(-20.0)
    assert any("outside the joint limits" in note for note in outside.notes)


def test_the_characteristic_length_scales_the_linear_rows_only() -> None:
    inputs = example("Panda")
    plain = run(inputs).result["poses"][0]
    scaled = run({**inputs, "characteristic_length": 2.0}).result["poses"][0]
    jac = np.asarray(plain["jacobian"])
    jac[:3] /= 2.0
    sigma = np.linalg.svd(jac, compute_uv=False)
    assert scaled["singular_values"] == pytest.approx(sigma.tolist(), rel=1e-12)
    assert scaled["inverse_condition"] == pytest.approx(sigma[-1] / sigma[0], rel=1e-12)
    assert scaled["manipulability"] == plain["manipulability"]  # the task Jacobian's own
