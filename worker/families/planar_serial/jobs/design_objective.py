"""What ``planar3r-design`` optimises: the search space, the designs and their score.

Variables: the links whose bounds leave them free (lo < hi: l1 and l2, and l3 only when
``link_bounds`` is given; a held l3 has lo = hi) and, with a base box, the base
(bx, by).  A candidate whose links add up to more than ``total_length_max`` is moved
onto that budget towards its lower bounds (so every evaluated design is feasible and
within its bounds); the score of a design is

* ``max_min_dz``: -min d_z + 1e-6 (total / total_max) (ties go to the shorter arm);
* ``min_length``: total / total_max (at most 1) if min d_z >= dz_target, else
  1 + (dz_target - min d_z) + 1e-6 (total / total_max): any design meeting the target
  beats any design missing it, and among those missing it the closest wins.

d_z is exact: the closed form for revolute joints, the closed-form events under joint
limits (:mod:`..kinematics.limited_exact`), a whole population of designs at once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_serial.kinematics.limited_exact import events_dexterity
from worker.families.planar_serial.kinematics.study_kernel import closed_form_dexterity

__all__ = [
    "Design",
    "DesignObjective",
    "SearchSpace",
    "dexterity_at",
    "dexterity_of_designs",
]

FloatArray = NDArray[np.float64]
Links = tuple[float, float, float]

#: Weight of the tie-breaking total length in the score.
TIE_BREAK = 1e-6
#: d_z within this of the target counts as meeting it.
TARGET_TOL = 1e-12


def dexterity_of_designs(
    links: FloatArray, bases: FloatArray, points: FloatArray, joint_limits_rad: FloatArray | None
) -> FloatArray:
    """Exact d_z (s, n) of s designs, links (s, 3) with bases (s, 2), at the task-frame
    points (n, 2).  The search space's designs are trusted (within their validated
    bounds): the kinematics do not check them again."""
    relative = points[np.newaxis, :, :] - bases[:, np.newaxis, :]
    rows = np.asarray(links[:, np.newaxis, :], dtype=np.float64)
    if joint_limits_rad is None:
        d_z = closed_form_dexterity(rows, relative)
    else:
        d_z = events_dexterity(rows, relative, joint_limits_rad)
    return np.asarray(d_z, dtype=float)


def dexterity_at(
    links: Links, base: tuple[float, float], points: FloatArray, joint_limits_rad: FloatArray | None
) -> FloatArray:
    """Exact d_z (...) of the arm with its base at ``base`` at task-frame points (..., 2)
    (trusted links, as :func:`dexterity_of_designs`)."""
    relative = np.asarray(points - np.asarray(base), dtype=np.float64)
    lengths = np.asarray(links, dtype=np.float64)
    if joint_limits_rad is None:
        d_z = closed_form_dexterity(lengths, relative)
    else:
        d_z = events_dexterity(lengths, relative, joint_limits_rad)
    return np.asarray(d_z, dtype=float)


@dataclass(frozen=True)
class SearchSpace:
    """Bounds of the links (3, 2), a held link as [value, value], the total length
    budget and the optional base box."""

    link_bounds: FloatArray
    total_max: float
    base_box: tuple[float, float, float, float] | None

    @property
    def free_links(self) -> NDArray[np.bool_]:
        """(3,) the links the search varies (lo < hi)."""
        return np.asarray(self.link_bounds[:, 0] < self.link_bounds[:, 1], dtype=bool)

    @property
    def bounds(self) -> list[tuple[float, float]]:
        """[lo, hi] of each variable: the free links, then the base's x and y."""
        box = self.base_box
        extra = [] if box is None else [(box[0], box[1]), (box[2], box[3])]
        links = self.link_bounds[self.free_links]
        return [(float(lo), float(hi)) for lo, hi in links] + extra

    def designs(self, x: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The designs candidates (variables, s) stand for: links (s, 3) within the
        budget, bases (s, 2)."""
        lower, upper = self.link_bounds[:, 0], self.link_bounds[:, 1]
        free = self.free_links
        count = int(free.sum())
        links = np.tile(lower, (x.shape[1], 1))
        links[:, free] = np.clip(x[:count].T, lower[free], upper[free])
        total = links.sum(axis=1, keepdims=True)
        spare = float(lower.sum())
        over = total > self.total_max  # onto the budget, towards the lower bounds
        scale = (self.total_max - spare) / np.where(over, total - spare, 1.0)
        links = np.where(over, lower + (links - lower) * scale, links)
        bases = np.zeros((x.shape[1], 2)) if self.base_box is None else x[count:].T
        return links, np.array(bases, dtype=float)

    def design(self, x: FloatArray) -> tuple[Links, tuple[float, float]]:
        """The design one candidate (variables,) stands for: links and base."""
        links, bases = self.designs(np.asarray(x, dtype=float)[:, np.newaxis])
        l1, l2, l3 = (float(v) for v in links[0])
        return (l1, l2, l3), (float(bases[0, 0]), float(bases[0, 1]))


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
    """The score of candidates over the evaluation points (n, 2) in the task frame."""

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

    def scores(self, min_dz: FloatArray, total_length: FloatArray) -> FloatArray:
        """Scores (s,) of designs with these smallest d_z and total lengths (s,)."""
        budget_share = total_length / self.space.total_max
        if self.objective == "max_min_dz":
            return np.asarray(-min_dz + TIE_BREAK * budget_share, dtype=float)
        met = min_dz >= self.dz_target - TARGET_TOL
        missed = 1.0 + (self.dz_target - min_dz) + TIE_BREAK * budget_share
        return np.asarray(np.where(met, budget_share, missed), dtype=float)

    def score(self, design: Design) -> float:
        return float(self.scores(np.array([design.min_dz]), np.array([design.total_length]))[0])

    def population_scores(self, x: FloatArray) -> FloatArray:
        """Scores (s,) of candidates (variables, s), evaluated together."""
        links, bases = self.space.designs(np.asarray(x, dtype=float))
        self.evaluations += links.shape[0]
        d_z = dexterity_of_designs(links, bases, self.points, self.joint_limits_rad)
        return self.scores(d_z.min(axis=1), links.sum(axis=1))

    def __call__(self, x: FloatArray) -> float:
        """The score of one candidate (variables,)."""
        return float(self.population_scores(np.asarray(x, dtype=float)[:, np.newaxis])[0])
