"""A finished job's outcome stamped with what computed it: ``provenance`` and
``result_hash`` in the result document, and the same two in every NPZ file's
``metadata`` entry (CSV files are left as they are: their first line is the header).

The NPZ format (:mod:`worker.common.data_export` writes it) is defined here, for the
runtime reads it: data arrays beside JSON description entries.
"""

from __future__ import annotations

import io
import json
import zipfile
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from worker.contract import Artifact
from worker.provenance.result_hash import npz_arrays_digest, result_hash

__all__ = ["NPZ_DESCRIPTION_ENTRIES", "NPZ_MEDIA_TYPE", "stamp_outcome"]

NPZ_MEDIA_TYPE = "application/x-npz"
#: The NPZ entries that describe the others (JSON strings).
NPZ_DESCRIPTION_ENTRIES = ("axes", "units", "metadata")
#: The time every member of a stamped NPZ file carries: none of the job's own.
_ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)


def _npz_bytes(entries: Mapping[str, Any]) -> bytes:
    """A compressed NPZ of ``entries``, byte for byte the same for the same arrays (the
    zip members carry no time; ``numpy.savez_compressed`` stamps the current one)."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, value in entries.items():
            info = zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_EPOCH)
            info.compress_type = zipfile.ZIP_DEFLATED
            with archive.open(info, "w", force_zip64=True) as member:
                np.lib.format.write_array(member, np.asanyarray(value), allow_pickle=False)
    return buffer.getvalue()


def _with_metadata(artifact: Artifact, stamp: Mapping[str, Any]) -> Artifact:
    """The NPZ ``artifact`` with ``stamp`` merged into its ``metadata`` entry (one
    without that entry is returned as it is)."""
    with np.load(io.BytesIO(artifact.data), allow_pickle=False) as archive:
        if "metadata" not in archive.files:
            return artifact
        entries = {name: archive[name] for name in archive.files}
    metadata = json.loads(str(entries["metadata"]))
    metadata.update(stamp)
    entries["metadata"] = np.array(json.dumps(metadata, allow_nan=False))
    return Artifact(artifact.name, artifact.media_type, _npz_bytes(entries), artifact.title)


def stamp_outcome(
    result: Mapping[str, Any], artifacts: Sequence[Artifact], provenance: Mapping[str, Any]
) -> tuple[dict[str, Any], list[Artifact]]:
    """``result`` with ``provenance`` and its ``result_hash`` (over the result and the
    NPZ files' data arrays), and ``artifacts`` with the NPZ files stamped alike."""
    files = {
        artifact.name: npz_arrays_digest(artifact.data, NPZ_DESCRIPTION_ENTRIES)
        for artifact in artifacts
        if artifact.media_type == NPZ_MEDIA_TYPE
    }
    digest = result_hash(result, files)
    stamp = {"provenance": dict(provenance), "result_hash": digest}
    stamped = [
        _with_metadata(artifact, stamp) if artifact.name in files else artifact
        for artifact in artifacts
    ]
    return {**result, **stamp}, stamped
