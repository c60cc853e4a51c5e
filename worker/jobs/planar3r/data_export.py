"""Map data as downloadable artifacts: CSV (one row per grid node) and NPZ."""

from __future__ import annotations

import io

import numpy as np
from numpy.typing import NDArray

from worker.contract import Artifact

__all__ = ["CSV_MEDIA_TYPE", "NPZ_MEDIA_TYPE", "dexterity_csv", "npz_artifact"]

CSV_MEDIA_TYPE = "text/csv"
NPZ_MEDIA_TYPE = "application/x-npz"
CSV_COLUMNS = ("x", "y", "distance", "d_z", "D", "region")
#: Grid nodes formatted per block, to bound the temporary strings on large maps.
CSV_BLOCK_NODES = 131_072


def dexterity_csv(
    name: str,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    d_z: NDArray[np.float64],
    region: NDArray[np.int8],
    title: str,
) -> Artifact:
    """CSV with columns x, y, distance, d_z, D, region: one row per node, row by row in y.

    ``x`` (nx,), ``y`` (ny,), ``d_z`` and ``region`` (ny, nx); floats with 12
    significant digits.  Formatted column-wise in blocks of grid rows: a 2001 x 2001
    map is about 230 MB of text.
    """
    x_text = _formatted(x)
    distance = np.hypot(x[None, :], y[:, None])
    buffer = io.BytesIO()
    buffer.write((",".join(CSV_COLUMNS) + "\n").encode("ascii"))
    rows_per_block = max(1, CSV_BLOCK_NODES // max(1, x.size))
    for start in range(0, y.size, rows_per_block):
        stop = min(start + rows_per_block, y.size)
        y_text = [text for text in _formatted(y[start:stop]) for _ in range(x.size)]
        block_dz = d_z[start:stop]
        columns = (
            x_text * (stop - start),
            y_text,
            _formatted(distance[start:stop]),
            _formatted(block_dz),
            _formatted(block_dz / 3.0),
            [str(r) for r in region[start:stop].ravel().tolist()],
        )
        lines = map(",".join, zip(*columns, strict=True))
        buffer.write(("\n".join(lines) + "\n").encode("ascii"))
    return Artifact(name, CSV_MEDIA_TYPE, buffer.getvalue(), title)


def _formatted(values: NDArray[np.float64]) -> list[str]:
    return [f"{v:.12g}" for v in values.ravel().tolist()]


def npz_artifact(name: str, arrays: dict[str, NDArray[np.generic]], title: str) -> Artifact:
    """A compressed NumPy archive holding ``arrays`` (load with ``numpy.load``)."""
    buffer = io.BytesIO()
    np.savez_compressed(buffer, allow_pickle=False, **arrays)
    return Artifact(name, NPZ_MEDIA_TYPE, buffer.getvalue(), title)
