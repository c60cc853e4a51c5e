"""Solver variables <-> designs inside the design space (docs/methods/spherical-parallel.md).

With D1, D2 the design-space half-widths (eq 19) at the current (beta, gamma) over the
CONTINUOUS workspace, free link angles are ``a1 - a2 = s D1``, ``a1 + a2 - pi = t D2``,
s, t in [-1, 1]; with one link angle fixed at a, the other is ``lo + u (hi - lo)``,
u in [0, 1], on its feasible interval [max(a - D1, pi - a - D2), min(a + D1, pi - a + D2)];
with both fixed, only (beta, gamma) that admit them decode. beta and gamma are solver
variables in their bounds (gamma = beta for identical platforms). Angles in rad.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from worker.families.spherical_parallel.kinematics.design_space import (
    EDGE_TOLERANCE,
    design_widths,
    link_angles,
)
from worker.families.spherical_parallel.kinematics.model import FloatArray, SpmDesign, Workspace

__all__ = ["EDGE_SHARE", "Parametrisation"]

#: Share of screening candidates put on a bound of each link-angle variable (an edge of
#: the design space): a third, half of it on each side.
EDGE_SHARE = 1.0 / 3.0
_LINK_VARIABLES = ("s", "t", "u")


class Parametrisation:
    """Solver variables (``names``, box ``lower``-``upper``) <-> feasible designs.

    D1, D2 are cached per (beta, gamma) for the life of the object (one optimisation).
    """

    def __init__(
        self,
        ws: Workspace,
        free: tuple[str, ...],
        identical: bool,
        fixed: Mapping[str, float],
        bounds: Mapping[str, tuple[float, float]],
    ) -> None:
        self.ws, self.free, self.identical, self.fixed = ws, free, identical, fixed
        alphas = [name for name in ("alpha1", "alpha2") if name in free]
        names = {2: ["s", "t"], 1: ["u"], 0: []}[len(alphas)]
        limits = {2: [(-1.0, 1.0)] * 2, 1: [(0.0, 1.0)], 0: []}[len(alphas)]
        for name in ("beta", "gamma"):
            if name in free:
                names.append(name)
                limits.append(bounds[name])
        self.names = tuple(names)
        self.lower = np.array([lo for lo, _ in limits])
        self.upper = np.array([hi for _, hi in limits])
        self._widths: dict[tuple[float, float], tuple[float, float]] = {}

    def widths(self, beta: float, gamma: float) -> tuple[float, float]:
        key = (beta, gamma)
        if key not in self._widths:
            self._widths[key] = design_widths(self.ws, beta, gamma)
        return self._widths[key]

    def decode(self, x: FloatArray) -> tuple[SpmDesign | None, float]:
        """(design, 0) or (None, gap > 0 in rad) for solver variables x."""
        values = dict(zip(self.names, (float(v) for v in x), strict=True))
        beta = values.get("beta", self.fixed.get("beta", 0.0))
        gamma = beta if self.identical else values.get("gamma", self.fixed.get("gamma", 0.0))
        d1, d2 = self.widths(beta, gamma)
        if "s" in values:
            a1, a2 = link_angles(values["s"], values["t"], d1, d2)
        elif "u" in values:
            free_name = "alpha1" if "alpha1" in self.free else "alpha2"
            held = self.fixed["alpha2" if free_name == "alpha1" else "alpha1"]
            lo = max(held - d1, math.pi - held - d2)
            hi = min(held + d1, math.pi - held + d2)
            if lo > hi + EDGE_TOLERANCE:
                return None, lo - hi
            angle = lo + values["u"] * max(hi - lo, 0.0)
            a1, a2 = (angle, held) if free_name == "alpha1" else (held, angle)
        else:
            a1, a2 = self.fixed["alpha1"], self.fixed["alpha2"]
            gap = max(abs(a1 - a2) - d1, abs(a1 + a2 - math.pi) - d2)
            if gap > EDGE_TOLERANCE:
                return None, gap
        if not (0.0 < a1 < math.pi and 0.0 < a2 < math.pi):
            return None, max(-a1, a1 - math.pi, -a2, a2 - math.pi, 0.0) + EDGE_TOLERANCE
        return SpmDesign(a1, a2, beta, gamma), 0.0

    def candidates(self, rng: np.random.Generator, count: int) -> FloatArray:
        """``count`` solver-variable vectors (count, len(names)) for screening starts.

        Uniform in the variable box, except that each link-angle variable (s, t or u) is
        put on one of its two bounds with probability :data:`EDGE_SHARE`: those bounds are
        the edges of the design space (eq 19), where the optima of Tables 1 and 2 sit
        (docs/methods/spherical-parallel.md) and which uniform draws never reach.
        """
        x = rng.uniform(self.lower, self.upper, size=(count, len(self.names)))
        for column, name in enumerate(self.names):
            if name in _LINK_VARIABLES:
                on_edge = rng.random(count) < EDGE_SHARE
                bound = np.where(rng.random(count) < 0.5, self.lower[column], self.upper[column])
                x[:, column] = np.where(on_edge, bound, x[:, column])
        return x
