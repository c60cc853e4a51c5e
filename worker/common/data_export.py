"""Job data as downloadable artifacts: CSV tables (one row per node or entry) and NPZ.

Shared by every job family; each family names its own columns and arrays.
"""

from __future__ import annotations

import io
from collections.abc import Callable, Mapping

import numpy as np
from numpy.typing import NDArray

from worker.contract import Artifact

__all__ = ["CSV_MEDIA_TYPE", "NPZ_MEDIA_TYPE", "columns_csv", "npz_artifact"]

CSV_MEDIA_TYPE = "text/csv"
NPZ_MEDIA_TYPE = "application/x-npz"
#: Rows formatted per block, to bound the temporary strings on large tables.
CSV_BLOCK_ROWS = 131_072


def columns_csv(
    name: str,
    columns: Mapping[str, NDArray[np.generic]],
    title: str,
    on_progress: Callable[[int, int], None] | None = None,
) -> Artifact:
    """CSV with one column per entry of ``columns`` (names in order), one row per element.

    Every column is raveled (C order) and must hold the same number of elements.
    Floats are written with 12 significant digits (NaN as ``nan``), integers and
    booleans as integers (``1``/``0``).  Formatted in blocks of rows, so a table of
    millions of rows never holds all its text twice; ``on_progress(rows_done, rows)``
    is called after each block.
    """
    arrays = [np.asarray(values).ravel() for values in columns.values()]
    sizes = {a.size for a in arrays}
    if len(sizes) > 1:
        raise ValueError(
            "The 'columns' parameter of columns_csv must hold arrays of one size. "
            f"Got sizes {[a.size for a in arrays]} instead."
        )
    rows = sizes.pop() if sizes else 0
    buffer = io.BytesIO()
    buffer.write((",".join(columns) + "\n").encode("ascii"))
    for start in range(0, rows, CSV_BLOCK_ROWS):
        stop = min(start + CSV_BLOCK_ROWS, rows)
        texts = [_formatted(a[start:stop]) for a in arrays]
        lines = map(",".join, zip(*texts, strict=True))
        buffer.write(("\n".join(lines) + "\n").encode("ascii"))
        if on_progress is not None:
            on_progress(stop, rows)
    return Artifact(name, CSV_MEDIA_TYPE, buffer.getvalue(), title)


def _formatted(values: NDArray[np.generic]) -> list[str]:
    if values.dtype.kind in "biu":
        return [str(int(v)) for v in values.tolist()]
    return [f"{v:.12g}" for v in values.astype(float).tolist()]


def npz_artifact(name: str, arrays: Mapping[str, NDArray[np.generic]], title: str) -> Artifact:
    """A compressed NumPy archive holding ``arrays`` (load with ``numpy.load``)."""
    buffer = io.BytesIO()
    np.savez_compressed(buffer, allow_pickle=False, **arrays)
    return Artifact(name, NPZ_MEDIA_TYPE, buffer.getvalue(), title)
