"""Argument checks of :func:`~.optimisation.optimise`.

Each returns its argument normalised (tuples, floats, defaults filled in) or raises a
ValueError naming the parameter of ``optimise``. Angles are in radians.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence

from worker.common.parameter_errors import bad_parameter

__all__ = [
    "DEFAULT_BOUNDS",
    "PARAMETERS",
    "checked_bounds",
    "checked_count",
    "checked_fixed",
    "checked_free",
    "checked_tolerance",
]

PARAMETERS = ("alpha1", "alpha2", "beta", "gamma")
#: Search ranges (rad) of beta and gamma unless ``bounds`` says otherwise.
DEFAULT_BOUNDS: Mapping[str, tuple[float, float]] = {
    "beta": (math.radians(1.0), math.radians(179.0)),
    "gamma": (0.0, math.radians(179.0)),
}
_FUNCTION = "optimise"


def checked_free(free: Sequence[str], identical: bool) -> tuple[str, ...]:
    names = tuple(free) if isinstance(free, Sequence) and not isinstance(free, str) else ()
    allowed = PARAMETERS[:3] if identical else PARAMETERS
    if not names or len(set(names)) != len(names) or not set(names) <= set(allowed):
        requirement = f"a non-empty sequence of distinct names from {allowed}" + (
            " (gamma follows beta with identical_platforms)" if identical else ""
        )
        raise bad_parameter("free", _FUNCTION, requirement, free)
    return tuple(p for p in PARAMETERS if p in names)


def checked_fixed(
    fixed: Mapping[str, float] | None, free: tuple[str, ...], identical: bool
) -> dict[str, float]:
    needed = [p for p in PARAMETERS if p not in free and not (identical and p == "gamma")]
    values = dict(fixed or {})
    if "gamma" in needed:
        values.setdefault("gamma", 0.0)
    ok = set(values) == set(needed) and all(
        isinstance(values[p], numbers.Real)
        and (values[p] >= 0.0 if p == "gamma" else values[p] > 0.0)
        and values[p] < math.pi
        for p in needed
    )
    if not ok:
        raise bad_parameter(
            "fixed", _FUNCTION, f"angles in rad for exactly {needed} (gamma defaults to 0)", fixed
        )
    return {p: float(values[p]) for p in needed}


def checked_bounds(
    bounds: Mapping[str, tuple[float, float]] | None,
) -> dict[str, tuple[float, float]]:
    merged = {**DEFAULT_BOUNDS, **(bounds or {})}
    ok = set(merged) == {"beta", "gamma"} and all(
        isinstance(pair, tuple)
        and len(pair) == 2
        and all(isinstance(v, numbers.Real) for v in pair)
        and (pair[0] >= 0.0 if name == "gamma" else pair[0] > 0.0)
        and pair[0] < pair[1] < math.pi
        for name, pair in merged.items()
    )
    if not ok:
        raise bad_parameter(
            "bounds", _FUNCTION, "{'beta' or 'gamma': (lo, hi)} rad with 0 < lo < hi < pi "
            "(0 <= lo for gamma)", bounds,
        )  # fmt: skip
    return {name: (float(lo), float(hi)) for name, (lo, hi) in merged.items()}


def checked_count(value: object, parameter: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise bad_parameter(parameter, _FUNCTION, "a positive integer", value)
    return int(value)


def checked_tolerance(value: object) -> float | None:
    if value is None:
        return None
    if not (isinstance(value, numbers.Real) and math.isfinite(float(value)) and float(value) > 0):
        raise bad_parameter(
            "singularity_tolerance", _FUNCTION, "None or a finite lambda > 0 (eq 30)", value
        )
    return float(value)
