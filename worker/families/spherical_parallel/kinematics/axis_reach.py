"""How close the platform axis of leg 1 comes to a fixed direction over a workspace.

The limited-torsion half of the design space (docs/methods/spherical-parallel.md, eqs 16-19):
D1 and D2 are the least angles between v_1 and -n_1, n_1 over the CONTINUOUS workspace.
v_1 is a low-order trigonometric polynomial of x = (f1, psi2, psi3), f1 = -psi1 (the terms of
:class:`~.indices.SampleSet` at eta = 0), so the least chord
|v_1 - t| is found from the discrete local minima of a grid, each polished by projected
Newton steps (polar tilt coordinates; good at minima above zero), then the best ends and
the best point of the face psi2 = 0 re-polished by projected Gauss-Newton in Cartesian
tilt coordinates (good at zeros of |v_1 - t|, which may sit next to that face, where
the polar coordinates are singular, or on a torsion bound; e.g. beta ~ gamma).
Angles in rad.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.ndimage import minimum_filter

from worker.families.spherical_parallel.kinematics.model import FloatArray, Workspace

__all__ = ["least_angle", "platform_axis", "search_grid_counts"]

_POLISHED = 6  # at most this many grid minima polished per bound...
_MARGIN = 0.1  # ...of those within this chord^2 of the least grid value
_FD_STEP = 1e-6  # finite-difference step (rad) of the polar polish's Hessian
_NEGATIVE_CURVATURE = 1e-6  # eigenvalue below -this: a saddle direction...
_SADDLE_STEP = 0.1  # ...followed with this first step (rad), halved until |v - t| falls
_GN_STEP = 1e-7  # central-difference step (rad) of the Cartesian polish's Jacobian
_ZERO_SEARCHES = 2  # best polar ends re-polished in Cartesian coordinates


def platform_axis(x: FloatArray, beta: float) -> FloatArray:
    """v_1 (3, ...) in the leg-1 frame (k, h, z) at x = (f1, psi2, psi3) (..., 3), f1 = -psi1.

    The terms of :class:`~.indices.SampleSet` at eta = 0.
    """
    sb, cb = math.sin(beta), math.cos(beta)
    f1, tilt, f2 = x[..., 0], x[..., 1], x[..., 0] + x[..., 2]
    s1, c1, s2, c2 = np.sin(f1), np.cos(f1), np.sin(f2), np.cos(f2)
    st, ct = np.sin(tilt), np.cos(tilt)
    return np.stack([sb * (s1 * c2 - ct * c1 * s2) + cb * st * c1,
                     sb * (c1 * c2 + ct * s1 * s2) - cb * st * s1,
                     sb * st * s2 + cb * ct])  # fmt: skip


def _chord(x: list[float], sb: float, cb: float, t: FloatArray) -> tuple[float, list[float]]:
    """|v_1(x) - t|^2 and its gradient in x = (f1, psi2, psi3), with the math module."""
    f1, tilt, f2 = x[0], x[1], x[0] + x[2]
    s1, c1, s2, c2 = math.sin(f1), math.cos(f1), math.sin(f2), math.cos(f2)
    st, ct = math.sin(tilt), math.cos(tilt)
    v = (sb * (s1 * c2 - ct * c1 * s2) + cb * st * c1,
         sb * (c1 * c2 + ct * s1 * s2) - cb * st * s1,
         sb * st * s2 + cb * ct)  # fmt: skip
    d_f2 = (-sb * (s1 * s2 + ct * c1 * c2), sb * (ct * s1 * c2 - c1 * s2), sb * st * c2)
    d_tilt = (sb * st * c1 * s2 + cb * ct * c1, -sb * st * s1 * s2 - cb * ct * s1,
              sb * ct * s2 - cb * st)  # fmt: skip
    d_f1 = (v[1] + d_f2[0], -v[0] + d_f2[1], d_f2[2])  # f2 moves with f1
    d = (v[0] - t[0], v[1] - t[1], v[2] - t[2])
    grad = [2.0 * (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) for r in (d_f1, d_tilt, d_f2)]
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2], grad


def _descend(
    x: list[float],
    step: FloatArray,
    value: float,
    bounds: tuple[FloatArray, FloatArray],
    axis: tuple[float, float, FloatArray],
) -> tuple[float, list[float], list[float]] | None:
    """Backtracking along ``step`` (projected on the bounds) until |v - t|^2 falls."""
    for _ in range(30):
        trial = list(np.clip(np.array(x) + step, *bounds))
        trial_value, trial_grad = _chord(trial, *axis)
        if trial_value < value:
            return trial_value, trial, trial_grad
        step = 0.5 * step
    return None


def _polish(
    x: list[float], lower: FloatArray, upper: FloatArray, beta: float, t: FloatArray
) -> tuple[float, list[float]]:
    """Projected Newton (finite-difference Hessian of the exact gradient) from x: the
    least |v_1 - t|^2 found and where. Bounds hold on psi2 and psi3; f1 is periodic.
    Where the Hessian is indefinite the step follows the most negative curvature (both
    ways), so that a start on a symmetry plane (zero gradient across it) leaves a saddle."""
    axis = (math.sin(beta), math.cos(beta), t)
    value, grad = _chord(x, *axis)
    for _ in range(60):
        g = np.array(grad)
        free = ~(((x <= lower) & (g > 0.0)) | ((x >= upper) & (g < 0.0)))
        if not free.any():
            break
        hessian = np.array([_chord([*x[:i], x[i] + _FD_STEP, *x[i + 1:]], *axis)[1]
                            for i in range(3)]) - g  # fmt: skip
        hessian = (0.5 / _FD_STEP) * (hessian + hessian.T)
        curvature, axes = np.linalg.eigh(hessian[np.ix_(free, free)])
        steps = [np.zeros(3), np.zeros(3)]
        if curvature[0] < -_NEGATIVE_CURVATURE:
            steps[0][free], steps[1][free] = _SADDLE_STEP * axes[:, 0], -_SADDLE_STEP * axes[:, 0]
        elif float(np.max(np.abs(g[free]))) < 1e-14:
            break
        else:
            steps = [np.zeros(3)]
            steps[0][free] = -(axes @ ((axes.T @ g[free]) / np.maximum(curvature, 1e-12)))
        found = [r for r in (_descend(x, st, value, (lower, upper), axis) for st in steps) if r]
        if not found:
            break
        new_value, new_x, grad = min(found)
        moved = max(abs(a - b) for a, b in zip(new_x, x, strict=True))
        x, value = new_x, new_value
        if moved < 1e-15:
            break
    return value, x


def _grid_minima(values: FloatArray, margin: float) -> NDArray[np.intp]:
    """Flat indices of the discrete local minima of a (n1, n2, n3) grid, periodic in
    axis 0, within ``margin`` of the least value, best first (at most _POLISHED)."""
    lowest = minimum_filter(values, size=3, mode=["wrap", "constant", "constant"], cval=np.inf)
    minimum = values <= lowest
    candidates = np.flatnonzero(minimum & (values <= values.min() + margin))
    return candidates[np.argsort(values.ravel()[candidates])][:_POLISHED]


def _tilted_axis(y: FloatArray, sb: float, cb: float) -> FloatArray:
    """v_1 at Cartesian tilt coordinates y = (psi2 cos f1, psi2 sin f1, psi3)."""
    f1, tilt = math.atan2(y[1], y[0]), math.hypot(y[0], y[1])
    s1, c1, s2, c2 = math.sin(f1), math.cos(f1), math.sin(f1 + y[2]), math.cos(f1 + y[2])
    st, ct = math.sin(tilt), math.cos(tilt)
    return np.array([sb * (s1 * c2 - ct * c1 * s2) + cb * st * c1,
                     sb * (c1 * c2 + ct * s1 * s2) - cb * st * s1,
                     sb * st * s2 + cb * ct])  # fmt: skip


def _project(y: FloatArray, ws: Workspace) -> FloatArray:
    radius = math.hypot(y[0], y[1])
    scale = min(1.0, ws.tilt_max / radius) if radius > 0.0 else 1.0
    return np.array([y[0] * scale, y[1] * scale, min(max(y[2], ws.torsion[0]), ws.torsion[1])])


def _polish_cartesian(x: list[float], ws: Workspace, beta: float, t: FloatArray) -> float:
    """Projected Gauss-Newton on |v_1 - t|^2 in Cartesian tilt coordinates from the polar
    point x = (f1, psi2, psi3): converges fast onto a zero of |v_1 - t|, wherever it is."""
    sb, cb = math.sin(beta), math.cos(beta)
    y = np.array([x[1] * math.cos(x[0]), x[1] * math.sin(x[0]), x[2]])
    residual = _tilted_axis(y, sb, cb) - t
    value = float(residual @ residual)
    for iteration in range(40):
        jac = np.empty((3, 3))
        for j in range(3):
            dy = np.zeros(3)
            dy[j] = _GN_STEP
            jac[:, j] = (_tilted_axis(y + dy, sb, cb) - _tilted_axis(y - dy, sb, cb)) / (
                2.0 * _GN_STEP
            )
        # v_1 stays on the unit sphere: jac has rank 2, so truncate the third direction
        step = np.linalg.lstsq(jac, -residual, rcond=1e-6)[0]
        for _ in range(8):  # a step that must shrink more is not closing in on a zero
            trial = _project(y + step, ws)
            trial_residual = _tilted_axis(trial, sb, cb) - t
            if float(trial_residual @ trial_residual) < value:
                break
            step *= 0.5
        else:
            break
        moved = float(np.max(np.abs(trial - y)))
        y, residual, previous = trial, trial_residual, value
        value = float(residual @ residual)
        if moved < 1e-15 or value < 1e-30:
            break
        if iteration >= 3 and value > 0.5 * previous:  # not heading for a zero: stop
            break
    return value


def search_grid_counts(ws: Workspace) -> tuple[int, int, int]:
    """(n1, n2, n3) of the search grid of :func:`least_angle` over (f1, psi2, psi3): 10° in
    f1, T/8 in psi2, at most 15° (and at least 5 values) over a torsion range."""
    lo, hi = ws.torsion
    torsion = 1 if hi == lo else max(5, math.ceil((hi - lo) / math.radians(15.0)) + 1)
    return 36, 9, torsion


def _search_grid(ws: Workspace) -> FloatArray:
    """(n1, n2, n3, 3) grid over (f1, psi2, psi3) with :func:`search_grid_counts`."""
    lo, hi = ws.torsion
    n1, n2, n3 = search_grid_counts(ws)
    axes = (np.linspace(0.0, 2.0 * np.pi, n1, endpoint=False),
            np.linspace(0.0, ws.tilt_max, n2), np.linspace(lo, hi, n3))  # fmt: skip
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)


def least_angle(ws: Workspace, beta: float, target: FloatArray) -> float:
    """Least angle (rad) between v_1 (leg 1, platform half-angle beta) and the unit vector
    ``target`` (3,), given in the leg-1 frame (k, h, z), over the workspace ``ws``."""
    grid = _search_grid(ws)
    chord2 = np.sum((platform_axis(grid, beta) - target[:, None, None, None]) ** 2, axis=0)
    # No polar polish starts on the face psi2 = 0: the azimuth does nothing there (a
    # plateau of equal grid minima, and a zero gradient in f1).
    inside = chord2.copy()
    inside[:, 0, :] = np.inf
    lower = np.array([-np.inf, 0.0, ws.torsion[0]])
    upper = np.array([np.inf, ws.tilt_max, ws.torsion[1]])
    starts = grid.reshape(-1, 3)[_grid_minima(inside, _MARGIN)]
    ends = sorted(_polish(list(map(float, x)), lower, upper, beta, target) for x in starts)
    best = min(ends[0][0], float(np.min(chord2)))
    if best > 1e-24:  # a zero may still hide next to a bound or the face psi2 = 0
        face = [0.0, 0.0, float(grid[0, 0, int(np.argmin(chord2[0, 0, :])), 2])]
        for x in [end[1] for end in ends[:_ZERO_SEARCHES]] + [face]:
            best = min(best, _polish_cartesian(x, ws, beta, target))
    return 2.0 * math.asin(min(1.0, math.sqrt(max(best, 0.0)) / 2.0))
