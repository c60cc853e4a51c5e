"""Column-wise description of W_kappa0 = {reachable, 1/kappa >= limit}.

See docs/methods/planar-parallel.md, "The well-conditioned workspace".

The paper finds the boundary of W_kappa0 by a 1-D root search (§III-C-1). Here the
search runs along vertical lines x = const ("columns"), batched over many columns and
many architectures of one type at once: each column is scanned on ``rows`` evenly spaced
heights, the lowest run of feasible samples is kept, and its two ends are refined to
~1e-12 by the Illinois (modified regula falsi) method on ``1/kappa - limit``, with
1/kappa extended by 0 outside the reachable set (1/kappa -> 0 at the reach boundary, so
the extension is continuous). Runs thinner than a row spacing can be missed; runs above
a gap in the same column (overhangs) are not part of the description. That is the
rectangle search's description (:mod:`.rectangle`); W_kappa0 itself, every run of
every column with thin runs found, is :mod:`.kappa_region`'s (:mod:`.column_runs`).

Internal to :mod:`.workspace`, :mod:`.kappa_region` and
:mod:`.sweep`; no input checks here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from worker.families.planar_parallel.kinematics.model import (
    Architecture,
    FloatArray,
    WorkingMode,
    inverse_condition_kernel,
)

__all__ = [
    "ArchitectureBatch",
    "bottom_runs",
    "crossing_near",
    "illinois",
    "isotropic_batch",
    "search_box",
    "single",
    "subset",
]

XTOL = 1e-12


@dataclass(frozen=True)
class ArchitectureBatch:
    """B architectures sharing the type, l1 and working mode of ``template``.

    l2, e, limit: (B,). Arrays passed to the methods have B on their first axis.
    """

    template: Architecture
    mode: WorkingMode
    l2: FloatArray
    e: FloatArray
    limit: FloatArray

    @property
    def size(self) -> int:
        return int(self.l2.size)

    def _per_row(self, values: FloatArray, ndim: int) -> FloatArray:
        return values.reshape((-1,) + (1,) * (ndim - 1))

    def inverse_condition(self, x: FloatArray, y: FloatArray) -> FloatArray:
        """1/kappa at (B, ...) points, NaN where unreachable."""
        return self._kernel(x, y, np.nan)

    def extended_inverse_condition(self, x: FloatArray, y: FloatArray) -> FloatArray:
        """1/kappa at (B, ...) points, extended by 0 where unreachable (1/kappa -> 0 at the
        reach boundary, so the extension is continuous)."""
        return self._kernel(x, y, 0.0)

    def _kernel(self, x: FloatArray, y: FloatArray, outside: float) -> FloatArray:
        ndim = max(np.ndim(x), np.ndim(y))
        l2, e = self._per_row(self.l2, ndim), self._per_row(self.e, ndim)
        return inverse_condition_kernel(self.template, self.mode, x, y, l2, e, outside)

    def margin(self, x: FloatArray, y: FloatArray) -> FloatArray:
        """1/kappa - limit, with 1/kappa = 0 where unreachable; >= 0 inside W_kappa0."""
        value = self.extended_inverse_condition(x, y)
        return value - self._per_row(self.limit, value.ndim)


def illinois(
    fun: Callable[[FloatArray], FloatArray],
    inside: FloatArray,
    outside: FloatArray,
    f_inside: FloatArray,
    f_outside: FloatArray,
    iterations: int = 60,
    xtol: float = XTOL,
) -> FloatArray:
    """Elementwise root of ``fun`` between ``inside`` (f >= 0) and ``outside`` (f < 0).

    Illinois variant of regula falsi (superlinear, bracketing). Returns the final
    bracket's ``inside`` end, so the answer keeps f >= 0 (conservative) and lies within
    ``xtol`` of the root unless ``iterations`` ran out.
    """
    a, b = inside.copy(), outside.copy()
    fa, fb = f_inside.copy(), f_outside.copy()
    last = np.zeros(a.shape, dtype=np.int8)  # +1: a moved last, -1: b moved last
    for _ in range(iterations):
        if a.size == 0 or float(np.max(np.abs(b - a))) < xtol:
            break
        denominator = fa - fb
        safe = np.where(denominator != 0.0, denominator, 1.0)
        c = np.where(denominator != 0.0, (b * fa - a * fb) / safe, 0.5 * (a + b))
        c = np.clip(c, np.minimum(a, b), np.maximum(a, b))
        fc = fun(c)
        moves_a = fc >= 0.0
        fb = np.where(moves_a & (last == 1), 0.5 * fb, fb)  # Illinois: halve the stale end
        fa = np.where(~moves_a & (last == -1), 0.5 * fa, fa)
        a, fa = np.where(moves_a, c, a), np.where(moves_a, fc, fa)
        b, fb = np.where(moves_a, b, c), np.where(moves_a, fb, fc)
        b = np.where(fa == 0.0, a, b)  # an exact root: regula falsi would stall on it
        last = np.where(moves_a, 1, -1).astype(np.int8)
    return a


def search_box(
    arch: Architecture, limit: float, x_half_span: float | None = None
) -> tuple[float, float, float]:
    """(X, y_low, y_high): W_kappa0 lies in |x| <= X, y_low <= y <= y_high.

    Proximal arm: the reach (|x| <= l1 + l2 - e, |y| <= l1 + l2). Telescopic leg: the
    legs' angle must lie in [g, pi - g], cos g = (1 - L^2)/(1 + L^2) for L = limit (eq 9
    with v1 = v2 = 1), so the point lies in the two circles through the pivots of radius
    e / sin g. Linear drive: |y| <= l2 and 1/kappa does not depend on x, so W_kappa0 is
    unbounded in x; X is ``x_half_span`` (default 2 l2). ``x_half_span`` overrides X for
    every type. X <= 0 means there is nothing to search.
    """
    if arch.actuation == "proximal-arm":
        reach = arch.l1 + arch.l2
        x_span, y_span = reach - arch.e, reach
    elif arch.actuation == "telescopic-leg":
        sin_g = 2.0 * limit / (1.0 + limit * limit)
        cos_g = (1.0 - limit * limit) / (1.0 + limit * limit)
        x_span = arch.e / sin_g
        y_span = arch.e * (1.0 + cos_g) / sin_g
    else:
        x_span, y_span = 2.0 * arch.l2, arch.l2
    if x_half_span is not None:
        x_span = x_half_span
    return float(x_span), -float(y_span), float(y_span)


def bottom_runs(
    batch: ArchitectureBatch,
    xs: FloatArray,
    y_low: FloatArray,
    y_high: FloatArray,
    rows: int,
) -> tuple[FloatArray, FloatArray]:
    """The lowest run of W_kappa0 in each column: (lower, upper), each (B, C), NaN if none.

    xs: (B, C) column abscissae; y_low, y_high: (B,) scan range; rows: samples per column.
    A run touching the scan range's end is cut there (no refinement at that end).
    """
    ys = y_low[:, None] + (y_high - y_low)[:, None] * np.linspace(0.0, 1.0, rows)  # (B, R)
    margins = batch.margin(xs[:, :, None], ys[:, None, :])  # (B, C, R)
    feasible = margins >= 0.0
    found = feasible.any(axis=-1)
    first_in = feasible.argmax(axis=-1)
    beyond = ~feasible & (np.arange(rows) > first_in[..., None])
    closed = beyond.any(axis=-1)
    first_out = np.where(closed, beyond.argmax(axis=-1), rows - 1)

    def at(values: FloatArray, index: np.ndarray) -> FloatArray:
        full = np.broadcast_to(values, margins.shape)
        return np.take_along_axis(full, index[..., None], axis=-1)[..., 0]

    ys_full = ys[:, None, :]
    below = np.maximum(first_in - 1, 0)
    last_in = np.maximum(first_out - 1, 0)
    lower = at(ys_full, first_in)
    upper = np.where(closed, at(ys_full, last_in), ys[:, None, -1])
    refine_lower = found & (first_in > 0)
    refine_upper = found & closed
    columns = np.concatenate([xs, xs], axis=1)
    inside = np.concatenate([lower, upper], axis=1)
    outside = np.concatenate(
        [np.where(refine_lower, at(ys_full, below), lower),
         np.where(refine_upper, at(ys_full, first_out), upper)], axis=1)  # fmt: skip
    f_inside = np.concatenate([at(margins, first_in), at(margins, last_in)], axis=1)
    f_outside = np.concatenate([at(margins, below), at(margins, first_out)], axis=1)
    refine = np.concatenate([refine_lower, refine_upper], axis=1)
    refined = inside.copy()
    if np.any(refine):
        rows_of = np.broadcast_to(np.arange(batch.size)[:, None], refine.shape)[refine]
        sub = subset(batch, rows_of)
        cols = columns[refine][:, None]
        refined[refine] = illinois(
            lambda y: sub.margin(cols, y[:, None])[:, 0],
            inside[refine], outside[refine], f_inside[refine], f_outside[refine],
        )  # fmt: skip
    count = xs.shape[1]
    lower, upper = refined[:, :count], refined[:, count:]
    return np.where(found, lower, np.nan), np.where(found, upper, np.nan)


def crossing_near(
    batch: ArchitectureBatch,
    x: FloatArray,
    ends: tuple[FloatArray, FloatArray],
    fraction: FloatArray,
    lower: bool,
    pad: FloatArray,
) -> FloatArray:
    """Exact run end (the lower one if ``lower``) at abscissae x (B,), between two columns
    whose run ends are ``ends`` ((B,) each), at ``fraction`` of the way from the first.

    The bracket is [min(ends) - pad, max(ends) + pad]; where it does not straddle the
    boundary the linear interpolation is returned instead; -inf (upper) or +inf (lower)
    where a column has no run.
    """
    v0, v1 = ends
    finite = np.isfinite(v0) & np.isfinite(v1)
    with np.errstate(invalid="ignore"):
        guess = np.where(finite, v0 + (v1 - v0) * fraction, np.inf if lower else -np.inf)
    low = np.where(finite, np.minimum(v0, v1) - pad, 0.0)
    high = np.where(finite, np.maximum(v0, v1) + pad, 0.0)
    inside, outside = (high, low) if lower else (low, high)
    f_in, f_out = batch.margin(x, inside), batch.margin(x, outside)
    valid = np.flatnonzero(finite & (f_in >= 0.0) & (f_out < 0.0))
    if valid.size == 0:
        return guess
    sub, xv = subset(batch, valid), x[valid]
    exact = illinois(lambda y: sub.margin(xv, y), inside[valid], outside[valid],
                     f_in[valid], f_out[valid])  # fmt: skip
    result = guess.copy()
    result[valid] = exact
    return result


def subset(batch: ArchitectureBatch, rows: np.ndarray) -> ArchitectureBatch:
    """One architecture per element of ``rows`` (indices into the batch)."""
    return ArchitectureBatch(
        batch.template, batch.mode, batch.l2[rows], batch.e[rows], batch.limit[rows]
    )


def single(arch: Architecture, mode: WorkingMode, limit: float) -> ArchitectureBatch:
    """A batch of one."""
    return ArchitectureBatch(arch, mode, np.array([arch.l2]), np.array([arch.e]), np.array([limit]))


def isotropic_batch(deltas: FloatArray, limit: float, mode: WorkingMode) -> ArchitectureBatch:
    """The eq-(12) proximal-arm family, l1 = 1, l2 = delta, e = (sqrt 2 / 2)(delta - 1)."""
    template = Architecture("proximal-arm", 1.0, 1.0, 0.0)
    e = math.sqrt(0.5) * (deltas - 1.0)
    return ArchitectureBatch(template, mode, deltas.copy(), e, np.full(deltas.shape, limit))
