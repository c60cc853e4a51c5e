"""The one wording of every bad-parameter error raised by the kinematics modules.

"The 'links' parameter of limited_orientation_dexterity must be three finite positive
lengths. Got (1, -2, 3) instead." — the parameter, the public function that received it,
what it must be, and what it was (long arrays by their shape, not their values).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["bad_parameter"]

#: Longer reprs are replaced by the array's shape (or cut).
_SHOWN_CHARS = 80


def bad_parameter(parameter: str, function: str, requirement: str, got: Any) -> ValueError:
    """The ValueError for ``parameter`` of ``function`` failing ``requirement``."""
    shown = repr(got)
    if len(shown) > _SHOWN_CHARS:
        try:
            shown = f"an array of shape {np.shape(got)}"
        except ValueError:  # ragged nested sequences have no shape
            shown = shown[: _SHOWN_CHARS - 3] + "..."
    return ValueError(
        f"The {parameter!r} parameter of {function} must be {requirement}. Got {shown} instead."
    )
