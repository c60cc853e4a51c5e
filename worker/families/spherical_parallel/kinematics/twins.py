"""Designs that score exactly like a given one (docs/methods/spherical-parallel.md, "Twins").

Each twin reproduces every 1/kappa of the original on the samples shifted by ``shift``
(rad, added to (psi1, psi2, psi3)); on the continuous workspace the shift changes
nothing, and on the default layouts a shift of pi in psi1 maps the samples onto
themselves (so do shifts of pi in psi3 for gamma = 0).

* (pi - a1, pi - a2, -branch): the same mechanism with every middle axis w_i -> -w_i
  (th_i -> th_i + pi): A -> -A, B -> -B, J unchanged at the same pose.
* gamma > 0: (a1, a2, pi - beta, pi - gamma, -branch) at psi1 + pi — both pyramids
  flipped, u_i -> -Rz(pi) u_i and v_i* -> -Rz(pi) v_i*, so the pose Rz(pi) Q Rz(pi)^T
  has the original's J up to a rotation (keeps beta = gamma; holds for any torsion range).
  Composed with the first: (pi - a1, pi - a2, pi - beta, pi - gamma, branch).
* Full-turn torsion, independent platforms: (a1, pi - a2, pi - beta, -branch) at
  psi3 + pi (v_i -> -v_i) and its composition with the first, (pi - a1, a2, pi - beta,
  branch).

(A further exact symmetry, not a different design: mirroring the whole mechanism in the
y-z plane maps psi to (pi - psi1, psi2, -psi3) and flips the branch; the default sample
layouts are mirror-symmetric, so there both branches score the same.) Angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike

from worker.families.spherical_parallel.kinematics.indices import (
    Indices,
    SampleSet,
    indices_from_batch,
)
from worker.families.spherical_parallel.kinematics.model import SpmDesign, Workspace, checked_branch

__all__ = ["TwinDesign", "twin_designs"]

_PI = math.pi


@dataclass(frozen=True)
class TwinDesign:
    """A design scoring exactly like another (see the module doc).

    shift: rad added to (psi1, psi2, psi3) of the samples to reproduce the original's
    values; indices: evaluated on the shifted samples with ``branch``.
    """

    design: SpmDesign
    branch: int
    shift: tuple[float, float, float]
    relation: str
    indices: Indices


def _table(
    design: SpmDesign, ws: Workspace, sign: int, identical: bool
) -> list[tuple[SpmDesign, int, tuple[float, float, float], str]]:
    a1, a2, beta, gamma = design.alpha1, design.alpha2, design.beta, design.gamma
    table = [(replace(design, alpha1=_PI - a1, alpha2=_PI - a2), -sign, (0.0, 0.0, 0.0),
              "(180 - a1, 180 - a2), opposite branch: the same mechanism")]  # fmt: skip
    if _PI - gamma < _PI:  # gamma > 0 (a tiny gamma would round pi - gamma to pi)
        flipped = replace(design, beta=_PI - beta, gamma=_PI - gamma)
        table += [
            (flipped, -sign, (_PI, 0.0, 0.0),
             "(a1, a2, 180 - beta, 180 - gamma), opposite branch, psi1 + 180"),
            (replace(flipped, alpha1=_PI - a1, alpha2=_PI - a2), sign, (_PI, 0.0, 0.0),
             "(180 - a1, 180 - a2, 180 - beta, 180 - gamma), same branch, psi1 + 180"),
        ]  # fmt: skip
    if ws.full_turn and not identical:
        table += [
            (replace(design, alpha2=_PI - a2, beta=_PI - beta), -sign, (0.0, 0.0, _PI),
             "(a1, 180 - a2, 180 - beta), opposite branch, torsion origin + 180"),
            (replace(design, alpha1=_PI - a1, beta=_PI - beta), sign, (0.0, 0.0, _PI),
             "(180 - a1, a2, 180 - beta), same branch, torsion origin + 180"),
        ]  # fmt: skip
    return table


def twin_designs(
    design: SpmDesign, ws: Workspace, samples: ArrayLike, branch: int, identical: bool = False
) -> tuple[TwinDesign, ...]:
    """The twins of ``design`` on branch ``branch`` (see the module doc), each with its
    indices on ``samples`` (n, 3) rad shifted by its ``shift``. identical: beta = gamma
    must hold (drops the full-turn twins, which change beta only)."""
    sign = checked_branch(branch, "twin_designs")
    base = SampleSet.from_samples(samples, "twin_designs")
    twins = []
    for twin, twin_branch, shift, relation in _table(design, ws, sign, identical):
        shifted = SampleSet.from_samples(base.samples + np.array(shift), "twin_designs")
        indices = indices_from_batch(shifted.evaluate(twin, twin_branch), twin_branch)
        twins.append(TwinDesign(twin, twin_branch, shift, relation, indices))
    return tuple(twins)
