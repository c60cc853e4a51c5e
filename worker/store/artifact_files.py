"""Artifact data of the embedded store: files under the data directory.

Each attempt writes its own folder, ``<root>/<job>/<attempt>/<name>``: a file is
written under a temporary name, fsynced and renamed, so a reader never sees half a
file, and a stale attempt can never overwrite the files a committed attempt points
at (the job row names the attempt).  Folders of attempts that never committed are
removed when the job completes, fails or is dismissed.
"""

from __future__ import annotations

import errno
import os
import shutil
import uuid
from collections.abc import Iterator
from pathlib import Path

__all__ = ["CHUNK_BYTES", "ArtifactFiles", "checked_name"]

#: Bytes read per chunk when an artifact is streamed.
CHUNK_BYTES = 1 << 20

#: errno values that mean the disk (or quota) is full.
FULL_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG})


def checked_name(name: str) -> str:
    """An artifact or job name that is safe as one path component."""
    if not name or name in (".", "..") or "/" in name or "\\" in name or "\x00" in name:
        raise ValueError(f"The artifact name {name!r} is not a plain file name.")
    return name


class ArtifactFiles:
    """Artifact bytes as files under ``root``."""

    def __init__(self, root: Path) -> None:
        self.root = root

    def _folder(self, job_id: str, attempt: int) -> Path:
        return self.root / checked_name(job_id) / str(int(attempt))

    def write(self, job_id: str, attempt: int, name: str, data: bytes) -> None:
        """Write one artifact of one attempt durably (temp file, fsync, rename)."""
        folder = self._folder(job_id, attempt)
        folder.mkdir(parents=True, exist_ok=True)
        final = folder / checked_name(name)
        temp = folder / f".{name}.{uuid.uuid4().hex}.tmp"
        try:
            with open(temp, "wb") as handle:
                handle.write(data)
                handle.flush()
                os.fsync(handle.fileno())
            os.replace(temp, final)
        except BaseException:
            temp.unlink(missing_ok=True)
            raise
        dir_fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)

    def chunks(self, job_id: str, attempt: int, name: str) -> Iterator[bytes]:
        """The artifact's bytes, :data:`CHUNK_BYTES` at a time.

        The file is opened before the first chunk, so a dismissal while streaming does
        not cut the download short (the open file outlives its name).
        """
        handle = open(self._folder(job_id, attempt) / checked_name(name), "rb")  # noqa: SIM115
        return _read_chunks(handle)

    def delete(self, job_id: str, keep_attempt: int | None = None) -> None:
        """Remove the job's folders, all or all but ``keep_attempt``'s."""
        job_folder = self.root / checked_name(job_id)
        if not job_folder.is_dir():
            return
        if keep_attempt is None:
            shutil.rmtree(job_folder, ignore_errors=True)
            return
        for folder in job_folder.iterdir():
            if folder.name != str(int(keep_attempt)):
                shutil.rmtree(folder, ignore_errors=True)

    def delete_attempt(self, job_id: str, attempt: int) -> None:
        shutil.rmtree(self._folder(job_id, attempt), ignore_errors=True)

    def check_writable(self, min_free_bytes: int) -> None:
        """Raise OSError (ENOSPC, EROFS, EACCES, ...) unless a file can be written here
        and at least ``min_free_bytes`` are free."""
        self.root.mkdir(parents=True, exist_ok=True)
        probe = self.root / f".probe-{uuid.uuid4().hex}"
        try:
            probe.write_bytes(b"ok")
        finally:
            probe.unlink(missing_ok=True)
        free = shutil.disk_usage(self.root).free
        if free < min_free_bytes:
            raise OSError(errno.ENOSPC, f"only {free} bytes free under {self.root}")


def _read_chunks(handle: object) -> Iterator[bytes]:
    from io import BufferedReader

    assert isinstance(handle, BufferedReader)
    with handle:
        while chunk := handle.read(CHUNK_BYTES):
            yield chunk
