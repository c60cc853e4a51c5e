"""Impossible designs are refused before queuing, with a 422 that names the field and
says why: a planar2dof robot whose chains can never meet, a 3R map grid that holds no
reachable point, a spherical design that reaches no orientation of its workspace.
Each boundary is checked against an independent evaluation (the map itself)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.errors import InvalidInputs
from worker.families.planar_parallel import CONDITIONING_MAP as PLANAR2DOF_MAP
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_serial import DEXTERITY_MAP
from worker.families.spherical_parallel import CONDITIONING_MAP as SPM_MAP
from worker.families.spherical_parallel import kinematics as sp
from worker.processes import ProcessDefinition
from worker.submission import validate_inputs


def refusal(definition: ProcessDefinition, inputs: dict[str, Any]) -> dict[str, Any]:
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(definition, inputs)
    (error,) = info.value.errors
    return error


# -- planar2dof: the two chains can never meet ------------------------------------------


def test_planar2dof_chains_that_never_meet_are_refused() -> None:
    error = refusal(PLANAR2DOF_MAP, {"l1": 1, "l2": 1, "e": 5})
    assert error["field"] == "inputs.e"
    assert "can never meet" in error["message"] and "reachable set is empty" in error["message"]
    validate_inputs(PLANAR2DOF_MAP, {"l1": 1, "l2": 1, "e": 1.9})
    # Telescopic legs and linear drives always reach something.
    validate_inputs(PLANAR2DOF_MAP, {"actuation": "telescopic-leg", "e": 5})


@settings(max_examples=30, deadline=None, derandomize=True)
@given(st.floats(0.2, 3.0), st.floats(0.2, 3.0), st.floats(0.0, 8.0))
def test_the_planar2dof_refusal_is_exactly_an_empty_reachable_set(
    l1: float, l2: float, e: float
) -> None:
    accepted = True
    try:
        validate_inputs(PLANAR2DOF_MAP, {"l1": l1, "l2": l2, "e": e})
    except InvalidInputs as exc:
        accepted = not any("can never meet" in err["message"] for err in exc.errors)
        if accepted:  # refused for another reason (e.g. the lengths' ratio): not this check
            return
    # Independently: the map over a grid around both joints finds a reachable node
    # (well inside the annuli when e is clearly below l1 + l2).
    reach = l1 + l2
    x = np.linspace(-(e + reach), e + reach, 401)
    y = np.linspace(-reach, reach, 401)
    reachable = bool(pp.conditioning_map(pp.Architecture("proximal-arm", l1, l2, e), x, y)
                     .reachable.any())  # fmt: skip
    if e < 0.98 * reach:
        assert accepted and reachable
    if e >= reach:
        assert not accepted and not reachable


# -- planar3r: a grid that holds no reachable point --------------------------------------


@pytest.mark.parametrize(
    ("links", "bounds", "where"),
    [
        ([15, 14, 8], [100, 200, 100, 200], "beyond the reach"),
        ([15, 14, 8], [-100, -40, -5, 5], "beyond the reach"),
        ([30, 2, 2], [-5, 5, -5, 5], "inside the unreachable disk"),
    ],
)
def test_a_3r_grid_without_a_reachable_point_is_refused(
    links: list[float], bounds: list[float], where: str
) -> None:
    error = refusal(DEXTERITY_MAP, {"links": links, "grid": {"bounds": bounds}})
    assert error["field"] == "inputs.grid.bounds"
    assert "no reachable point" in error["message"] and where in error["message"]


@pytest.mark.parametrize("bounds", [[-1, 1, -1, 1], [20, 40, -5, 5], [36, 38, -1, 1]])
def test_a_3r_grid_that_meets_the_reach_is_accepted(bounds: list[float]) -> None:
    validate_inputs(DEXTERITY_MAP, {"links": [15, 14, 8], "grid": {"bounds": bounds}})


# -- spm: a design that reaches no orientation of its workspace --------------------------

WORKSPACE = {"tilt_max_deg": 45, "torsion_deg": [-180, 180]}


def spm_inputs(a1: float, a2: float, beta: float) -> dict[str, Any]:
    return {"alpha1_deg": a1, "alpha2_deg": a2, "beta_deg": beta, "workspace": WORKSPACE}


def test_an_spm_design_that_reaches_nothing_is_refused() -> None:
    error = refusal(SPM_MAP, spm_inputs(5, 5, 80))
    assert error["field"] == "inputs.workspace"
    assert "cannot reach the prescribed workspace at all" in error["message"]
    assert "spm-design-space" in error["message"]
    validate_inputs(SPM_MAP, spm_inputs(60, 90, 90))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(st.floats(2.0, 178.0), st.floats(2.0, 178.0), st.floats(2.0, 178.0))
def test_the_spm_refusal_agrees_with_a_denser_search(a1: float, a2: float, beta: float) -> None:
    try:
        validate_inputs(SPM_MAP, spm_inputs(a1, a2, beta))
        accepted = True
    except InvalidInputs:
        accepted = False
    design = sp.SpmDesign.from_degrees(a1, a2, beta, 0.0)
    ws = sp.Workspace(np.radians(45.0), (-np.pi, np.pi), True)
    dense = sp.boundary_grid(ws, azimuth=60, tilt=41, torsion=180)  # denser than the check
    reaches = bool(sp.inverse_kinematics(design, dense)[1].any())
    if not accepted:  # refused: a denser search finds nothing either
        assert not reaches
