"""dexlab for its users: a Python client (sync and async) and the ``dexlab`` command.

::

    from dexlab import Client

    with Client() as client:         # DEXLAB_URL (http://127.0.0.1:8000), DEXLAB_API_KEY
        job = client.run("planar2dof-conditioning-map", example=0)
        maps = job.arrays("conditioning_map.npz")   # x, y, inverse_condition, ...

Importing this package does no work and imports neither the server nor the worker: the
server-side commands (``dexlab serve``, ``dexlab worker``) import them when they run.
The client needs httpx (and numpy for :meth:`Job.arrays`).
"""

from __future__ import annotations

from dexlab.async_client import AsyncClient, AsyncJob
from dexlab.client import Client
from dexlab.documents import Artifact, JobStatus
from dexlab.errors import (
    CostLimitExceeded,
    DexlabError,
    IdempotencyConflict,
    InvalidInputs,
    JobDismissed,
    JobFailed,
    NoSuchArtifact,
    NoSuchJob,
    NoSuchProcess,
    NotFound,
    QuotaExceeded,
    RequestRefused,
    ResultNotReady,
    ServiceUnavailable,
    ServiceUnreachable,
    Unauthorized,
    WaitTimeout,
)
from dexlab.job import Job
from dexlab.quantities import ResultPaths, ResultQuantity
from dexlab.retry import RetryPolicy
from dexlab.robot_files import robot_from_file

__all__ = [
    "Artifact",
    "AsyncClient",
    "AsyncJob",
    "Client",
    "CostLimitExceeded",
    "DexlabError",
    "IdempotencyConflict",
    "InvalidInputs",
    "Job",
    "JobDismissed",
    "JobFailed",
    "JobStatus",
    "NoSuchArtifact",
    "NoSuchJob",
    "NoSuchProcess",
    "NotFound",
    "QuotaExceeded",
    "RequestRefused",
    "ResultNotReady",
    "ResultPaths",
    "ResultQuantity",
    "RetryPolicy",
    "ServiceUnavailable",
    "ServiceUnreachable",
    "Unauthorized",
    "WaitTimeout",
    "robot_from_file",
]
