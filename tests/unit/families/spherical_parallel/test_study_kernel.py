"""The study kernel of spm-conditioning-map against the process run per design: random
designs, inside and outside the angles' ranges and at their edges, over random
workspaces, samplings and branches, for random objectives among the covered paths.

The kernel's one shortcut: a design that reaches no orientation of its workspace is
refused by the process (at ``inputs.workspace``) but reported by the kernel as having
no value, when every objective read is an index over the samples (null unless every
sample is reachable) or the least 1/kappa on the boundary grid (null unless a grid
point is): infeasible either way.  The tests below prove it both ways: on designs
the process refuses, and by the kernel checking the reach exactly when an objective
is reported whatever the reach (a count, an echoed input)."""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.unit.worker.studies.engines import REGISTRY, assert_engines_agree, both_engines, field
from tests.unit.worker.studies.registry import STUDY
from worker.studies.rows import FEASIBLE, NO_VALUE, REFUSED

SHORTCUT = [("inputs.workspace", NO_VALUE)]
EDGES = [-5.0, 0.0, 1e-7, 1e-6, 20.0, 45.0, 60.0, 90.0, 120.0, 150.0, 179.999999,
         180.0 - 1e-7, 180.0]  # fmt: skip
SUMMARIES = ["indices.rms_inverse_condition", "indices.mean_square_inverse_condition",
             "indices.gci", "indices.min_inverse_condition", "indices.max_inverse_condition",
             "indices.min_abs_det_a", "workspace_minimum.inverse_condition"]  # fmt: skip
REPORTED_ANYWAY = ["indices.real_samples", "indices.samples", "indices.branch", "branch",
                   "design.alpha1_deg", "design.gamma_deg", "workspace_minimum.psi_deg[]|max",
                   "workspace_minimum.psi_deg[1]", "sampling.psi2_deg[]|mean",
                   "workspace.torsion_deg[]|sum", "sampling.counts.tilt",
                   "workspace_minimum.grid_points"]  # fmt: skip
ANGLES = ["alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg"]


def angle() -> st.SearchStrategy[float]:
    """Mostly angles of designs that reach a workspace, often an edge or beyond."""
    usual = st.floats(40.0, 140.0)
    return st.one_of(usual, usual, st.sampled_from(EDGES), st.floats(0.0, 180.0))


@st.composite
def studies(draw: st.DrawFn) -> dict[str, Any]:
    varied = draw(st.lists(st.sampled_from(ANGLES), min_size=1, max_size=2, unique=True))
    vary = {}
    for name in varied:
        lo, hi = sorted((draw(angle()), draw(angle())))
        vary[name] = [lo, hi, draw(st.integers(1, 3))]
    fixed: dict[str, Any] = {
        name: draw(st.one_of(st.floats(40.0, 140.0), st.floats(1.0, 179.0)))
        for name in ANGLES[:3]
        if name not in varied
    }
    if "gamma_deg" not in varied and draw(st.booleans()):
        fixed["gamma_deg"] = draw(st.sampled_from([0.0, 10.0, 90.0]))
    lo = draw(st.sampled_from([0.0, -15.0, -180.0]))
    turn = draw(st.booleans())
    workspace: dict[str, Any] = {
        "tilt_max_deg": draw(st.sampled_from([1e-6, 10.0, 30.0, 45.0, 60.0, 90.0, 120.0])),
        "torsion_deg": [lo, lo + (360.0 if turn else draw(st.sampled_from([1.0, 30.0])))],
    }
    if draw(st.booleans()):
        workspace["samples"] = {"azimuth": draw(st.integers(1, 4)),
                                "tilt": draw(st.integers(1, 3)),
                                "torsion": draw(st.integers(1, 3))}  # fmt: skip
    fixed["workspace"] = workspace
    fixed["branch"] = draw(st.sampled_from([-1, 1]))
    objectives = draw(st.lists(st.sampled_from(SUMMARIES + REPORTED_ANYWAY), min_size=1,
                               max_size=3, unique=True))  # fmt: skip
    return {
        "process": "spm-conditioning-map",
        "fixed": fixed,
        "vary": vary,
        "objectives": {name: draw(st.sampled_from(["max", "min"])) for name in objectives},
    }


@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])  # fmt: skip
@given(studies())
def test_the_kernel_agrees_with_the_process_design_by_design(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs, SHORTCUT)


def test_designs_the_process_refuses_for_their_reach_are_infeasible_either_way() -> None:
    """The first worked example (Bai's Example I over a 10° grid): the process refuses
    the designs that reach none of the cone; the kernel, reading indices only, reports
    them as having no value; asked for a count reported whatever the reach, it checks
    the reach and refuses exactly the same designs, at the same field."""
    inputs = dict(STUDY.examples[0].inputs)
    batched, per_design = assert_engines_agree(inputs, SHORTCUT)
    refused = per_design.codes == REFUSED
    assert refused.sum() == 24
    assert {field(per_design, n) for n in np.flatnonzero(refused)} == {"inputs.workspace"}
    assert (batched.codes[refused] == NO_VALUE).all()
    counted = {**inputs, "objectives": {"indices.real_samples": "max"}}
    batched, per_design = assert_engines_agree(counted)  # no shortcut allowed
    assert np.array_equal(batched.codes == REFUSED, refused)
    assert (batched.codes[~refused] == FEASIBLE).all()


def test_over_other_samples_the_kernel_checks_the_reach_of_every_scored_design() -> None:
    """Indices over samples other than the default ones do not show that a design
    reaches the reach check's grids: the kernel looks (and finds every scored design
    reaches, as the process does)."""
    inputs = {**dict(STUDY.examples[4].inputs)}
    inputs["sample"] = {**inputs["sample"], "count": 16}
    batched, _ = assert_engines_agree(inputs, SHORTCUT)
    assert (batched.codes == FEASIBLE).sum() > 0


def test_the_kernel_covers_what_it_declares() -> None:
    process = REGISTRY.get("spm-conditioning-map")
    assert process is not None and process.study_kernel is not None
    declared = {entry.path for entry in process.result_paths}
    assert set(process.study_kernel.covers) <= declared
    described = {e["path"]: e.get("kernel", False) for e in process.describe()["result_paths"]}
    assert {path for path, covered in described.items() if covered} == set(
        process.study_kernel.covers
    )


def test_a_grid_edge_is_refused_at_its_field_in_both_engines() -> None:
    inputs = {**dict(STUDY.examples[0].inputs), "vary": {"alpha1_deg": [0, 180, 3],
                                                         "alpha2_deg": [90, 90, 1]}}  # fmt: skip
    batched, per_design = assert_engines_agree(inputs, SHORTCUT)
    assert [field(batched, n) for n in range(3)] == ["inputs.alpha1_deg", "", "inputs.alpha1_deg"]
    assert [field(per_design, n) for n in range(3)] == [field(batched, n) for n in range(3)]
    assert both_engines(inputs)[0].codes.tolist()[::2] == [REFUSED, REFUSED]
