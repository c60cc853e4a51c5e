"""The robot a conditioning-map request describes, and the grid that shows its workspace.

:func:`architecture_from_spec` turns the validated inputs into a kinematic
:class:`~worker.families.planar_parallel.kinematics.Architecture` (e by eq 12 for
``"architecture": "isotropic"``); :func:`map_grid` gives the requested grid or one that
holds the whole reachable workspace of the type (docs/methods/planar-parallel.md, Fig. 1).
"""

from __future__ import annotations

import math

import numpy as np

from worker.common.grids import WorkspaceGrid
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.kinematics import study_kernel
from worker.families.planar_parallel.kinematics.study_kernel import DEFAULT_GRID_MARGIN
from worker.families.planar_parallel.specs import ConditioningMapSpec, GridSpec

__all__ = [
    "DEFAULT_GRID_MARGIN",
    "architecture_from_spec",
    "default_bounds",
    "map_grid",
    "robot_from_spec",
]


def architecture_from_spec(spec: ConditioningMapSpec) -> pp.Architecture:
    """The Architecture of the request; unused lengths are filled with l1 (never read)."""
    if spec.architecture == "isotropic":
        return pp.isotropic_architecture(_l2(spec), spec.l1)
    return pp.Architecture(spec.actuation, spec.l1, _l2(spec), spec.e or 0.0)


def robot_from_spec(spec: ConditioningMapSpec) -> pp.Robot:
    """The job's robot, checked once: its Architecture and working mode."""
    return pp.Robot(architecture_from_spec(spec), spec.working_mode)


def _l2(spec: ConditioningMapSpec) -> float:
    return spec.l2 if spec.l2 is not None else spec.l1


def default_bounds(arch: pp.Architecture) -> tuple[float, float, float, float]:
    """[x_min, x_max, y_min, y_max] around the type's reachable workspace, 3 % margin.

    Proximal arm: |x| <= l1 + l2 - e, |y| <= l1 + l2 (both chains reach); telescopic
    leg: the square |x|, |y| <= 3e (l1 if e = 0); linear drive: |x| <= 2 l2, |y| <= l2.
    The study kernel's bounds (:func:`.kinematics.study_kernel.default_bounds`) of one
    design, so that a study's grids are the job's.
    """
    lengths = np.array([[arch.l1, arch.l2, arch.e]])
    x0, x1, y0, y1 = study_kernel.default_bounds(arch.actuation, lengths)[0].tolist()
    return x0, x1, y0, y1


def map_grid(spec: GridSpec, arch: pp.Architecture) -> WorkspaceGrid:
    """The requested grid, or :func:`default_bounds` with the requested node count."""
    x0, x1, y0, y1 = spec.bounds if spec.bounds is not None else default_bounds(arch)
    return WorkspaceGrid((float(x0), float(x1), float(y0), float(y1)), spec.points_per_axis)


def describe_architecture(spec: ConditioningMapSpec, arch: pp.Architecture) -> str:
    """A one-line description for plot subtitles (mathtext), e.g. 'proximal-arm,
    $l_1$ = 1, ...'."""
    parts: list[str] = [spec.actuation]
    if spec.actuation != "telescopic-leg":
        if spec.actuation == "proximal-arm":
            parts.append(f"$l_1$ = {arch.l1:.4g}")
        parts.append(f"$l_2$ = {arch.l2:.4g}")
    if spec.actuation != "linear-drive":
        parts.append(f"$e$ = {arch.e:.4g}" + (" (eq 12)" if spec.architecture else ""))
    if spec.actuation == "proximal-arm":
        parts.append(rf"$\delta$ = {arch.l2 / arch.l1:.4g}")
    m1, m2 = spec.working_mode
    parts.append(f"working mode [{m1:+d}, {m2:+d}]")
    return ", ".join(parts)


def isotropic_depth(arch: pp.Architecture) -> float:
    """H = (√2/2)(l1 + l2), the depth of eq (12)'s isotropic point (0, -H)."""
    return math.sqrt(0.5) * (arch.l1 + arch.l2)
