"""A workspace input as the kinematics sees it, its samples, and how they are reported.

The job layer speaks degrees, :mod:`worker.families.spherical_parallel.kinematics` radians: the
conversion happens here and nowhere else. Every spm result reports its ``sampling``
(:func:`sampling_entry`) and its ``workspace`` (:func:`workspace_entry`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.workspace_spec import WorkspaceSpec

__all__ = [
    "DEFAULT_COUNTS",
    "FloatArray",
    "design_of",
    "kinematic_workspace",
    "sampling_entry",
    "workspace_entry",
    "workspace_samples",
]

FloatArray = NDArray[np.float64]
DEFAULT_COUNTS = (4, 12, 3)


def kinematic_workspace(spec: WorkspaceSpec) -> sp.Workspace:
    """The :class:`~worker.families.spherical_parallel.kinematics.Workspace` (rad) of ``spec``."""
    lo, hi = spec.torsion_deg
    if spec.full_turn:
        return sp.Workspace(math.radians(spec.tilt_max_deg), (math.radians(lo),
                            math.radians(lo) + 2.0 * math.pi), True)  # fmt: skip
    return sp.Workspace(
        math.radians(spec.tilt_max_deg), (math.radians(lo), math.radians(hi)), False
    )


def workspace_samples(spec: WorkspaceSpec) -> tuple[FloatArray, sp.SampleLayout]:
    """The equal-weight samples (n, 3) rad of ``spec`` and their layout."""
    counts = spec.samples
    return sp.orientation_samples(
        kinematic_workspace(spec), counts.azimuth, counts.tilt, counts.torsion
    )


def _degrees(values: tuple[float, ...]) -> list[float]:
    return [round(math.degrees(v), 10) for v in values]


def sampling_entry(layout: sp.SampleLayout) -> dict[str, Any]:
    """The sampling used, in degrees: counts, the angles along each axis and their rules."""
    return {
        "n": layout["n"],
        "counts": {
            "azimuth": layout["counts"][0],
            "tilt": layout["counts"][1],
            "torsion": layout["counts"][2],
        },
        "default": tuple(layout["counts"]) == DEFAULT_COUNTS,
        "order": "psi1 slowest, then psi2, then psi3 (the product psi1 x psi2 x psi3)",
        "psi1_deg": _degrees(layout["psi1"]),
        "psi2_deg": _degrees(layout["psi2"]),
        "psi3_deg": _degrees(layout["psi3"]),
        "psi1_rule": layout["psi1_rule"],
        "psi2_rule": layout["psi2_rule"],
        "psi3_rule": layout["psi3_rule"],
        "equal_weights": layout["equal_weights"],
    }


def workspace_entry(spec: WorkspaceSpec) -> dict[str, Any]:
    """The prescribed workspace as reported back."""
    return {
        "tilt_max_deg": spec.tilt_max_deg,
        "cone_opening_deg": 2.0 * spec.tilt_max_deg,
        "torsion_deg": list(spec.torsion_deg),
        "full_turn": spec.full_turn,
    }


def design_of(alpha1: float, alpha2: float, beta: float, gamma: float) -> sp.SpmDesign:
    """The kinematics' design (rad) from angles in degrees."""
    return sp.SpmDesign.from_degrees(alpha1, alpha2, beta, gamma)


def orientations_rad(psi_deg: object) -> FloatArray:
    """Orientations in degrees (..., 3) as radians, float64."""
    return np.radians(np.asarray(psi_deg, dtype=np.float64))
