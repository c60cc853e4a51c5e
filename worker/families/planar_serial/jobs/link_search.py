"""The search of ``planar3r-design``: differential evolution over the exact d_z, polished.

Variables: the links (l1, l2, l3) and, with a base box, the base (bx, by). A candidate
whose links add up to more than ``total_length_max`` is moved onto that budget towards
its lower bounds (so every evaluated design is feasible and within its bounds); the
score of a design is

* ``max_min_dz``: -min d_z + 1e-6 (total / total_max) (ties go to the shorter arm);
* ``min_length``: total / total_max (at most 1) if min d_z >= dz_target, else
  1 + (dz_target - min d_z) + 1e-6 (total / total_max): any design meeting the target
  beats any design missing it, and among those missing it the closest wins.

d_z is exact: the closed form for revolute joints, the closed-form events under joint
limits (:mod:`..kinematics.limited_exact`).  The score is a minimum over points of
piecewise-smooth functions with plateaus, kinks and many local optima, so the global
stage is scipy's differential evolution (gradient-free, seeded, all generations run);
SHGO was not chosen because it builds on local minimisers and a simplicial complex that
plateaus and kinks defeat.  Nelder-Mead (gradient-free too) then polishes the best
design within the same bounds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import OptimizeResult, differential_evolution, minimize

from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.design_spec import POLISH_EVALUATIONS_PER_VARIABLE
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
)

__all__ = [
    "Design",
    "DesignObjective",
    "SearchOutcome",
    "SearchSpace",
    "dexterity_at",
    "search",
]

FloatArray = NDArray[np.float64]
Links = tuple[float, float, float]

#: Weight of the tie-breaking total length in the score.
TIE_BREAK = 1e-6
#: d_z within this of the target counts as meeting it.
TARGET_TOL = 1e-12


def dexterity_at(
    links: Links, base: tuple[float, float], points: FloatArray, joint_limits_rad: FloatArray | None
) -> FloatArray:
    """Exact d_z (...) of the arm with its base at ``base`` at task-frame points (..., 2)."""
    relative = points - np.asarray(base)
    if joint_limits_rad is None:
        d_z = planar_serial.exact_orientation_dexterity(links, relative)
    else:
        d_z = exact_limited_orientation_dexterity(links, relative, joint_limits_rad)
    return np.asarray(d_z, dtype=float)


@dataclass(frozen=True)
class SearchSpace:
    """Bounds of the links (3, 2), the total length budget and the optional base box."""

    link_bounds: FloatArray
    total_max: float
    base_box: tuple[float, float, float, float] | None

    @property
    def bounds(self) -> list[tuple[float, float]]:
        box = self.base_box
        extra = [] if box is None else [(box[0], box[1]), (box[2], box[3])]
        return [(float(lo), float(hi)) for lo, hi in self.link_bounds] + extra

    def design(self, x: FloatArray) -> tuple[Links, tuple[float, float]]:
        """The design a candidate stands for: links within the budget, and the base."""
        lower = self.link_bounds[:, 0]
        links = np.clip(np.asarray(x[:3], dtype=float), lower, self.link_bounds[:, 1])
        total = float(links.sum())
        if total > self.total_max:  # onto the budget, towards the lower bounds
            spare = float(lower.sum())
            links = lower + (links - lower) * ((self.total_max - spare) / (total - spare))
        base = (0.0, 0.0) if self.base_box is None else (float(x[3]), float(x[4]))
        return (float(links[0]), float(links[1]), float(links[2])), base


@dataclass(frozen=True)
class Design:
    """One evaluated design: links, base, d_z at the evaluation points, summaries."""

    links: Links
    base: tuple[float, float]
    d_z: FloatArray

    @property
    def min_dz(self) -> float:
        return float(self.d_z.min())

    @property
    def mean_dz(self) -> float:
        return float(self.d_z.mean())

    @property
    def total_length(self) -> float:
        return math.fsum(self.links)


@dataclass
class DesignObjective:
    """The score of a candidate over the evaluation points (n, 2) in the task frame."""

    points: FloatArray
    joint_limits_rad: FloatArray | None
    objective: Literal["max_min_dz", "min_length"]
    dz_target: float
    space: SearchSpace
    evaluations: int = field(default=0)

    def evaluate(self, links: Links, base: tuple[float, float]) -> Design:
        return Design(links, base, dexterity_at(links, base, self.points, self.joint_limits_rad))

    def meets_target(self, design: Design) -> bool:
        return design.min_dz >= self.dz_target - TARGET_TOL

    def score(self, design: Design) -> float:
        length = TIE_BREAK * design.total_length / self.space.total_max
        if self.objective == "max_min_dz":
            return -design.min_dz + length
        if self.meets_target(design):
            return design.total_length / self.space.total_max
        return 1.0 + (self.dz_target - design.min_dz) + length

    def __call__(self, x: FloatArray) -> float:
        self.evaluations += 1
        return self.score(self.evaluate(*self.space.design(x)))


@dataclass(frozen=True)
class SearchOutcome:
    """The best design and how the search got there."""

    best: Design
    history: list[dict[str, float]]
    global_stage: dict[str, Any]
    polish: dict[str, Any]
    evaluations: int


def search(
    objective: DesignObjective,
    *,
    seed: int,
    population_size: int,
    generations: int,
    on_generation: Callable[[int, int], None],
) -> SearchOutcome:
    """Differential evolution (best1bin, Latin-hypercube start, no early stop), then
    Nelder-Mead from its best; ``on_generation(done, total)`` after each generation."""
    space = objective.space
    history: list[dict[str, float]] = []

    def record(x: FloatArray) -> None:
        design = objective.evaluate(*space.design(x))
        history.append({"generation": len(history), "min_dz": design.min_dz,
                        "total_length": design.total_length,
                        "score": objective.score(design)})  # fmt: skip

    def callback(intermediate_result: OptimizeResult) -> None:
        record(np.asarray(intermediate_result.x))
        on_generation(len(history) - 1, generations)

    found = differential_evolution(
        objective, space.bounds, strategy="best1bin", maxiter=generations,
        popsize=population_size, tol=0.0, atol=0.0, polish=False, init="latinhypercube",
        rng=np.random.default_rng(seed), callback=callback, updating="immediate",
    )  # fmt: skip
    de_evaluations = objective.evaluations
    polished = minimize(
        objective, found.x, method="Nelder-Mead", bounds=space.bounds,
        options={"maxfev": POLISH_EVALUATIONS_PER_VARIABLE * len(space.bounds),
                 "xatol": 1e-10, "fatol": 1e-13},
    )  # fmt: skip
    better = bool(polished.fun < found.fun)
    best_x = np.asarray(polished.x if better else found.x)
    best = objective.evaluate(*space.design(best_x))
    return SearchOutcome(
        best=best,
        history=history,
        global_stage={
            "method": "scipy.optimize.differential_evolution (best1bin)",
            "generations": int(found.nit),
            "population": population_size * len(space.bounds),
            "evaluations": de_evaluations,
            "best_score": float(found.fun),
            "message": str(found.message),
        },
        polish={
            "method": "Nelder-Mead",
            "evaluations": int(polished.nfev),
            "improved": better,
            "score_gain": float(found.fun - polished.fun) if better else 0.0,
            "message": str(polished.message),
        },
        evaluations=objective.evaluations,
    )
