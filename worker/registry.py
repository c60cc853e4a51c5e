"""The registry: every process dexlab ships, assembled from the families.

This is the one module of the runtime that names the families (the architecture test
checks that every folder under ``worker/families/`` is listed).  The families import
the contract (:mod:`worker.processes`), never this module; the design study is built
here with the registry of the processes it may study, and never builds one itself.
Nothing is built at import time: each call assembles a new registry.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Sequence

import worker.families
import worker.studies
from worker.families import chains, planar_parallel, planar_serial, serial, spherical_parallel
from worker.processes import FamilyPackage, ProcessRegistry
from worker.studies.chunk import study_chunk
from worker.studies.process import design_study

__all__ = [
    "build_registry",
    "default_registry",
    "family_packages",
    "preload_job_modules",
    "worker_registry",
]


def family_packages() -> tuple[FamilyPackage, ...]:
    """The families dexlab ships, in the order ``GET /v1/processes`` lists their
    processes: a new family is a folder under ``worker/families/`` and one entry here."""
    return (planar_serial, planar_parallel, chains, spherical_parallel, serial)


def build_registry(
    families: Sequence[FamilyPackage], *, with_chunks: bool = False
) -> ProcessRegistry:
    """The processes of ``families``, then ``design-study`` over them (and, for the
    workers, ``design-study-chunk``, which the service neither lists nor accepts)."""
    studied = ProcessRegistry(families=families)
    extra = (
        (design_study(studied), study_chunk(studied)) if with_chunks else (design_study(studied),)
    )
    return ProcessRegistry(extra, families=families)


def default_registry() -> ProcessRegistry:
    """Every public process dexlab ships, built on demand (no import-time work)."""
    return build_registry(family_packages())


def worker_registry() -> ProcessRegistry:
    """What the workers run: every public process and the jobs processes make for
    themselves (a study's chunks), which the service neither lists nor accepts."""
    return build_registry(family_packages(), with_chunks=True)


def preload_job_modules() -> list[str]:
    """Import every module a job imports when it runs (each family's ``jobs`` package
    with its figures, hence matplotlib; the design studies); the names, in order.

    Processes import their jobs' modules on first use, so the API stays light.  A
    prefork worker (``dexlab worker`` on Celery) calls this before it forks, so that each
    pool process, and each one started in place of a process that stopped, has them
    already (shared copy-on-write) instead of its first job paying the imports (about
    0.3 s for ``fourbar-grashof``, longer than a thousand such jobs take to run)."""
    packages = [
        f"{m.name}.jobs" for m in pkgutil.iter_modules(worker.families.__path__, "worker.families.")
    ]
    names: list[str] = []
    for package in (*packages, worker.studies.__name__):
        module = importlib.import_module(package)
        names.append(package)
        names += [m.name for m in pkgutil.iter_modules(module.__path__, f"{package}.")]
    for name in names:
        importlib.import_module(name)
    return names
