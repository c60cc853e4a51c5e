"""Hypothesis strategies the joint-limit tests share: three-link designs, angles and
joint limits (radians)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

lengths = st.floats(0.2, 5.0)
designs = st.tuples(lengths, lengths, lengths)
angles = st.floats(-math.pi, math.pi)


@st.composite
def limits(draw: st.DrawFn) -> np.ndarray:
    """Random limits; each joint free with probability 1/4."""
    rows = []
    for _ in range(3):
        if draw(st.integers(0, 3)) == 0:
            rows.append([-math.pi, math.pi])
        else:
            rows.append(sorted((draw(angles), draw(angles))))
    return np.array(rows)
