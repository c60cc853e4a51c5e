"""What computed a result: the dexlab build, the process version, the numerical
libraries and the backend, and the result key that names the computation.

The build is read once, when the settings tree is (``WorkerSettings.build``): the
package version plus ``DEXLAB_BUILD_ID`` when set, else the git commit of the source
checkout the package runs from, else nothing more.

The **result key** digests everything a result depends on: the process ID, its
canonical validated inputs (defaults filled in; ``plots`` included, for it changes the
files), the process's ``version``, the dexlab build and the numpy and scipy versions
(major.minor).  Two jobs with one key compute the same result.
"""

from __future__ import annotations

import hashlib
import platform
import subprocess
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import metadata as package_metadata
from pathlib import Path
from typing import Any

from worker.request_hash import canonical_json

__all__ = ["BuildInfo", "provenance_block", "read_build", "result_key"]

#: The libraries whose version is part of a result key (major.minor) and of provenance.
_LIBRARIES = ("numpy", "scipy")


@dataclass(frozen=True)
class BuildInfo:
    """The dexlab build: its package ``version``, a ``build`` label (the
    ``DEXLAB_BUILD_ID``, or ``git:<commit>``, or "" when neither is known), and the
    full versions of python, numpy and scipy it runs with."""

    version: str
    build: str
    libraries: tuple[tuple[str, str], ...] = ()

    @property
    def label(self) -> str:
        """``0.1.0+git:1a2b...`` (or the bare version without a build label)."""
        return f"{self.version}+{self.build}" if self.build else self.version


def _package_version(name: str) -> str:
    try:
        return package_metadata.version(name)
    except package_metadata.PackageNotFoundError:
        return "unknown"


def _git(source: Path, *args: str) -> str:
    return subprocess.run(
        ["git", "-C", str(source), *args], capture_output=True, text=True, timeout=5, check=True
    ).stdout.strip()


def _git_commit(source: Path) -> str:
    """The commit checked out where ``source`` lives ("" outside a git checkout); with
    edits to tracked files, ``-dirty.<digest of the diff>`` (so two different edits of
    one commit never share a result key)."""
    try:
        commit = _git(source, "rev-parse", "HEAD")
        diff = _git(source, "diff", "HEAD", "--", ".")
    except (OSError, subprocess.SubprocessError):
        return ""
    if not diff:
        return commit
    return f"{commit}-dirty.{hashlib.sha256(diff.encode()).hexdigest()[:12]}"


def read_build(build_id: str) -> BuildInfo:
    """The build running now: ``build_id`` (``DEXLAB_BUILD_ID``) when given, else the
    git commit of this source checkout (run once, at start-up)."""
    version = _package_version("dexlab")
    versions = [(name, _package_version(name)) for name in _LIBRARIES]
    libraries = (("python", platform.python_version()), *versions)
    if build_id:
        return BuildInfo(version, build_id, libraries)
    commit = _git_commit(Path(__file__).resolve().parents[1])
    return BuildInfo(version, f"git:{commit}" if commit else "", libraries)


def _major_minor(version: str) -> str:
    return ".".join(version.split(".")[:2])


def result_key(
    process_id: str, inputs: Mapping[str, Any], process_version: str, build: BuildInfo
) -> str:
    """SHA-256 naming one computation: the process, its canonical validated
    ``inputs``, its version, the dexlab build and numpy/scipy (major.minor)."""
    versions = dict(build.libraries)
    libraries = {name: _major_minor(versions.get(name, "unknown")) for name in _LIBRARIES}
    document = {
        "process": process_id,
        "inputs": dict(inputs),
        "process_version": process_version,
        "dexlab": build.label,
        "libraries": libraries,
    }
    return hashlib.sha256(canonical_json(document).encode()).hexdigest()


def provenance_block(
    process_id: str, process_version: str, build: BuildInfo, backend: str, key: str
) -> dict[str, Any]:
    """A result's ``provenance``: no job ID, owner, host or time, so a result shared
    by several jobs says the same for each."""
    return {
        "dexlab": {"version": build.version, "build": build.build},
        "process": {"id": process_id, "version": process_version},
        "libraries": dict(build.libraries),
        "backend": backend,
        "result_key": key,
    }
