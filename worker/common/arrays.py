"""Array aliases and the one argument check every family's kinematics uses.

:func:`checked_array` turns an argument into float64 data (a copy only if needed) or
raises the ValueError of :mod:`worker.common.parameter_errors` naming the parameter,
the function and what it must be.  Pure numpy.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from worker.common.parameter_errors import bad_parameter

__all__ = ["BoolArray", "FloatArray", "checked_array"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def checked_array(
    value: object,
    parameter: str,
    function: str,
    requirement: str,
    valid: Callable[[FloatArray], bool],
) -> FloatArray:
    """``value`` as a float64 array (a copy only if needed), or a ValueError naming it."""
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise bad_parameter(parameter, function, requirement, value) from None
    if not (np.all(np.isfinite(arr)) and valid(arr)):
        raise bad_parameter(parameter, function, requirement, value)
    return arr
