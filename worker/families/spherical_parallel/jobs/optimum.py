"""The optimum of ``spm-optimisation`` as reported: in the paper's convention, with twins.

The solver may end on any of the designs that score exactly alike
(docs/methods/spherical-parallel.md, "Twins: designs that score alike"): e.g. (134.8, 90, 90)
for Table 2's (45.2, 90, 90), or (180 - a1, 180 - a2, 180 - beta, 180 - gamma) with
identical platforms. On mirror-symmetric samples
(psi -> (180 - psi1, psi2, -psi3) maps them onto themselves, as the default layouts of a
full turn or of a torsion range symmetric about 0 do) the mirror image of the
supplementary twin, (180 - a1, 180 - a2) on the SAME branch, scores alike too: e.g.
(123.5, 92.7, 47.4) and (56.5, 87.3, 47.4) for Table 3. The job shows the one that reads
like the paper's tables, among those with the requested branch and the same eq 28 value
on the very same samples, and says which design the solver found.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.design_entries import (
    design_entry,
    design_space_check,
    indices_entry,
    minimum_entry,
)
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray

__all__ = ["MIRROR_RELATION", "SOLVER_RELATION", "Presented", "optimum_entry",
           "presented_optimum"]  # fmt: skip

#: Twins whose eq 28 value differs from the optimum's by at most this score the same.
_SAME_SCORE = 1e-9
#: "Above 90°" by more than the solver's rounding (optima sit at 90° ± 1e-5°).
_RIGHT_ANGLE = math.radians(90.001)
SOLVER_RELATION = "as found by the solver"
MIRROR_RELATION = (
    "(180 - a1, 180 - a2), same branch: the mirror image of the supplementary twin, equal "
    "on these mirror-symmetric samples"
)


@dataclass(frozen=True)
class Presented:
    """The optimum as reported: a design scoring exactly like the solver's best
    (docs/methods/spherical-parallel.md, "Twins") on the same samples and branch, in the
    paper's convention (beta <= 90, then alpha1 <= 90), with its indices."""

    design: sp.SpmDesign
    indices: sp.Indices
    relation: str
    twins: tuple[sp.TwinDesign, ...] = ()


def presented_optimum(
    outcome: sp.OptimisationResult, ws: sp.Workspace, samples: FloatArray, branch: int,
    identical: bool,
) -> Presented | None:  # fmt: skip
    """The solver's best design or the twin that reads like the paper's tables.

    A twin qualifies only with the requested branch and the same eq 28 value on the
    unshifted samples (to 1e-9), so nothing about the optimum changes but its angles; so
    does the mirrored supplementary twin (see the module doc), under the same check.
    """
    if outcome.design is None or outcome.indices is None:
        return None
    best = outcome.indices.mean_square_inverse_condition
    candidates = [Presented(outcome.design, outcome.indices, SOLVER_RELATION)]
    design = outcome.design
    mirrored = replace(design, alpha1=math.pi - design.alpha1, alpha2=math.pi - design.alpha2)
    others = [(t.design, t.relation) for t in outcome.twins if t.branch == branch]
    for other, relation in [*others, (mirrored, MIRROR_RELATION)]:
        indices = sp.workspace_indices(other, samples, branch)
        if abs(indices.mean_square_inverse_condition - best) <= _SAME_SCORE:
            candidates.append(Presented(other, indices, relation))

    def convention(candidate: Presented) -> tuple[bool, bool]:
        return (candidate.design.beta > _RIGHT_ANGLE, candidate.design.alpha1 > _RIGHT_ANGLE)

    shown = min(candidates, key=convention)
    twins = sp.twin_designs(shown.design, ws, samples, branch, identical)
    return replace(shown, twins=twins)


def optimum_entry(
    outcome: sp.OptimisationResult, shown: Presented, ws: sp.Workspace
) -> dict[str, Any]:
    """The ``optimum`` of the result: the shown design, its indices, where it sits, its twins
    and (if it is a twin) the design the solver ended at."""
    assert outcome.design is not None
    twin_entries = [{
        **design_entry(twin.design), "branch": twin.branch,
        "shift_deg": [round(math.degrees(v), 10) for v in twin.shift], "relation": twin.relation,
        "indices": indices_entry(twin.indices),
    } for twin in shown.twins]  # fmt: skip
    found = shown.relation == SOLVER_RELATION
    return {
        **design_entry(shown.design),
        "branch": outcome.branch,
        **indices_entry(shown.indices),
        "workspace_minimum": minimum_entry(sp.workspace_minimum(shown.design, ws, outcome.branch)),
        "design_space": design_space_check(shown.design, ws),
        "start": outcome.best_start,
        "found_as": None
        if found
        else {
            **design_entry(outcome.design),
            "relation": f"the shown design is its twin: {shown.relation}",
        },
        "twins": twin_entries,
    }
