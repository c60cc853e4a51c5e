"""The dexterity map's data files: CSV (one row per grid node) and NPZ.

The generic writers (:func:`~worker.common.data_export.columns_csv`,
:func:`~worker.common.data_export.npz_artifact`) live in :mod:`worker.common.data_export`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import (
    DIMENSIONLESS,
    column,
    columns_csv,
    job_metadata,
    npz_artifact,
)
from worker.common.grids import WorkspaceGrid
from worker.contract import Artifact
from worker.families.planar_serial.specs import DexterityMapSpec

__all__ = ["csv_columns", "dexterity_csv", "dexterity_map_files"]


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


def dexterity_map_files(
    spec: DexterityMapSpec,
    grid: WorkspaceGrid,
    d_z: NDArray[np.float64],
    region: NDArray[np.int8],
) -> tuple[Artifact, ...]:
    """The map's CSV and NPZ (x, y, d_z, D, region, links, joint limits, with units)."""
    limits = np.asarray(
        spec.joint_limits_deg if spec.joint_limits_deg is not None else np.full((3, 2), np.nan)
    )
    csv = dexterity_csv(
        "dexterity_map.csv", grid.x, grid.y, d_z, region, "Dexterity map (CSV)", spec.length_unit
    )
    length, none = spec.length_unit, DIMENSIONLESS
    npz = npz_artifact(
        "dexterity_map.npz",
        {
            "x": grid.x,
            "y": grid.y,
            "d_z": d_z,
            "D": d_z / 3.0,
            "region": region,
            "links": np.asarray(spec.links),
            "joint_limits_deg": limits,
        },
        "Dexterity map (NumPy arrays)",
        units={
            "x": length,
            "y": length,
            "d_z": none,
            "D": none,
            "region": none,
            "links": length,
            "joint_limits_deg": "deg",
        },
        axes={
            "d_z": ("y", "x"),
            "D": ("y", "x"),
            "region": ("y", "x"),
            "links": ("link",),
            "joint_limits_deg": ("joint", "bound"),
        },
        metadata=job_metadata("planar3r-dexterity-map", spec.model_dump(mode="json")),
    )
    return csv, npz
