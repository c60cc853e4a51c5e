"""The dexterity map as a CSV artifact (one row per grid node).

The generic writers (:func:`~worker.common.data_export.columns_csv`,
:func:`~worker.common.data_export.npz_artifact`) live in :mod:`worker.common.data_export`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import DIMENSIONLESS, column, columns_csv
from worker.contract import Artifact

__all__ = ["csv_columns", "dexterity_csv"]


def csv_columns(length_unit: str) -> tuple[str, ...]:
    """The CSV's column names: x, y and distance in ``length_unit``; d_z, D and the
    region code dimensionless."""
    lengths = tuple(column(q, length_unit) for q in ("x", "y", "distance"))
    return (*lengths, *(column(q, DIMENSIONLESS) for q in ("d_z", "D", "region")))


def dexterity_csv(
    name: str,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    d_z: NDArray[np.float64],
    region: NDArray[np.int8],
    title: str,
    length_unit: str,
) -> Artifact:
    """CSV with columns x, y, distance, d_z, D, region (names with their units, see
    :func:`csv_columns`): one row per node, row by row in y.

    ``x`` (nx,), ``y`` (ny,), ``d_z`` and ``region`` (ny, nx); floats with 12
    significant digits.  A 2001 x 2001 map is about 230 MB of text.
    """
    xx, yy = np.meshgrid(x, y)
    values = (xx, yy, np.hypot(xx, yy), d_z, d_z / 3.0, region)
    return columns_csv(name, dict(zip(csv_columns(length_unit), values, strict=True)), title)
