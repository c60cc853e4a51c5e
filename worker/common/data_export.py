"""Job data as downloadable artifacts that describe themselves: CSV and NPZ.

Shared by every job family; each family names its own columns and arrays.

- **CSV**: the first line is the header (no preamble), one row per node or entry, and
  every column name carries its unit: ``x [mm]``, ``inverse_condition [-]``
  (dimensionless), ``joint_1_angle [deg]``.  One name per quantity, whatever the
  options.  :func:`column` builds a name; :func:`columns_csv` refuses one without a unit.
- **NPZ** (``numpy.load(f)``, no pickle): the arrays, the axis vectors beside them, and
  three JSON strings: ``axes`` (each array's dimensions in order, by the names of the
  1-D axis vectors or of counts: ``{"inverse_condition": ["y", "x"]}``), ``units``
  (every array's unit) and ``metadata`` (the process, its inputs, the software).
  ``json.loads(str(data["axes"]))`` reads one.
"""

from __future__ import annotations

import io
import json
import re
from collections.abc import Callable, Mapping, Sequence
from importlib import metadata as package_metadata
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.contract import Artifact
from worker.provenance.stamp import NPZ_DESCRIPTION_ENTRIES, NPZ_MEDIA_TYPE

__all__ = [
    "CSV_MEDIA_TYPE",
    "DIMENSIONLESS",
    "NPZ_DESCRIPTION_ENTRIES",
    "NPZ_MEDIA_TYPE",
    "angle_or_pure",
    "column",
    "columns_csv",
    "job_metadata",
    "named_column",
    "npz_artifact",
]

CSV_MEDIA_TYPE = "text/csv"
#: Rows formatted per block, to bound the temporary strings on large tables.
CSV_BLOCK_ROWS = 131_072
#: The unit of a pure number (a ratio, an index, a count, a flag).
DIMENSIONLESS = "-"
#: A CSV column name: a quantity and its unit in brackets.
_COLUMN = re.compile(r"^[A-Za-z][A-Za-z0-9_]* \[[^\[\],\n]+\]$")


def column(quantity: str, unit: str) -> str:
    """The CSV column name of ``quantity`` in ``unit``: ``"x [mm]"``."""
    name = f"{quantity} [{unit}]"
    if not _COLUMN.match(name):
        raise ValueError(f"The 'quantity' and 'unit' of column must make a name like "
                         f"'x [mm]'. Got {name!r} instead.")  # fmt: skip
    return name


def angle_or_pure(name: str) -> str:
    """The unit of an array named by dexlab's convention: ``*_deg`` is in degrees, any
    other name a pure number."""
    return "deg" if name.endswith("_deg") else DIMENSIONLESS


def named_column(name: str) -> str:
    """The CSV column of an array so named: ``"alpha1_deg"`` -> ``"alpha1 [deg]"``,
    ``"nfev"`` -> ``"nfev [-]"``."""
    return column(name.removesuffix("_deg"), angle_or_pure(name))


def job_metadata(process_id: str, inputs: Mapping[str, Any]) -> dict[str, Any]:
    """What an NPZ's ``metadata`` holds: the process, its inputs (as validated, JSON)
    and the software that wrote it."""
    try:
        version = package_metadata.version("dexlab")
    except package_metadata.PackageNotFoundError:  # pragma: no cover - not installed
        version = "unknown"
    return {"process": process_id, "inputs": dict(inputs), "software": f"dexlab {version}"}


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
    unnamed = [name for name in columns if not _COLUMN.match(name)]
    if unnamed:
        raise ValueError(
            "The 'columns' parameter of columns_csv must name every column with its unit "
            f"('x [mm]', 'ratio [-]'). Got {unnamed} instead."
        )
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


def npz_artifact(
    name: str,
    arrays: Mapping[str, NDArray[np.generic]],
    title: str,
    *,
    units: Mapping[str, str],
    axes: Mapping[str, Sequence[str]],
    metadata: Mapping[str, Any],
) -> Artifact:
    """A compressed NumPy archive holding ``arrays`` and their description.

    ``units``: every array's unit (:data:`DIMENSIONLESS` for pure numbers). ``axes``:
    the dimensions of the arrays that have any, in order; each name is a 1-D array of
    ``arrays`` whose length is that dimension's (an axis vector such as ``"x"``), or a
    name of your choice for a plain count (``"sample"``). ``metadata``: JSON-able
    (:func:`job_metadata`). Stored as JSON strings under :data:`NPZ_DESCRIPTION_ENTRIES`;
    load with ``numpy.load`` (no pickle).
    """
    reserved = set(arrays) & set(NPZ_DESCRIPTION_ENTRIES)
    missing = sorted(set(arrays) - set(units))
    unknown = sorted((set(units) | set(axes)) - set(arrays))
    if reserved or missing or unknown:
        raise ValueError(
            "The 'arrays', 'units' and 'axes' parameters of npz_artifact must describe the "
            f"same arrays. Got reserved names {sorted(reserved)}, arrays without a unit "
            f"{missing} and descriptions of no array {unknown} instead."
        )
    for array_name, dims in axes.items():
        shape = np.shape(arrays[array_name])
        if len(dims) != len(shape):
            raise ValueError(
                f"The 'axes' parameter of npz_artifact must give {array_name!r} one name per "
                f"dimension. Got {list(dims)} for shape {shape} instead."
            )
        for dim, size in zip(dims, shape, strict=True):
            if dim in arrays and np.shape(arrays[dim]) != (size,):
                raise ValueError(
                    f"The 'axes' parameter of npz_artifact names {dim!r} as a dimension of "
                    f"{array_name!r} of length {size}. Got an axis of shape "
                    f"{np.shape(arrays[dim])} instead."
                )
    described = {
        "axes": json.dumps({k: list(v) for k, v in axes.items()}),
        "units": json.dumps(dict(units)),
        "metadata": json.dumps(dict(metadata), allow_nan=False),
    }
    buffer = io.BytesIO()
    np.savez_compressed(
        buffer, allow_pickle=False, **arrays, **{k: np.array(v) for k, v in described.items()}
    )
    return Artifact(name, NPZ_MEDIA_TYPE, buffer.getvalue(), title)
