"""Committing a finished attempt's outcome to the store, through store trouble.

The store retries transient faults itself for a few seconds; here the attempt keeps
trying for longer (its guard thread keeps the lease alive meanwhile), so a store
outage shorter than that costs nothing.  A longer outage gives up and lets the lease
lapse: the job is retried by another attempt, never lost.  Faults that waiting cannot
cure fail the job once, with the cause, instead of recomputing it: a full disk is
``storage-full``, an unusable store ``storage-error``.
"""

from __future__ import annotations

import logging
import time
import traceback
from collections.abc import Mapping, Sequence
from typing import Any

from worker.contract import Artifact
from worker.errors import StorageError, StorageFull, StoreUnavailable
from worker.store.base import Claim, JobStore

__all__ = ["commit_outcome", "error_document", "record_failure"]

log = logging.getLogger("dexlab.worker")

#: Longest pause between two tries of a commit (seconds).
_MAX_PAUSE_S = 2.0


def error_document(exc: BaseException) -> dict[str, Any]:
    """The failure a job's own exception records."""
    return {
        "type": "job-error",
        "title": "The job raised an error",
        "detail": f"{type(exc).__name__}: {exc}",
        "traceback": traceback.format_exception(exc)[-5:],
    }


def _storage_failure(exc: StoreUnavailable, attempt: int) -> dict[str, Any]:
    full = isinstance(exc, StorageFull)
    return {
        "type": "storage-full" if full else "storage-error",
        "title": "Storage full" if full else "Storage error",
        "detail": f"The results of attempt {attempt} could not be stored: {exc.detail}",
    }


def record_failure(
    store: JobStore, claim: Claim, error: Mapping[str, Any], give_up_after_s: float
) -> bool:
    """Record the attempt's failure, retrying store trouble for ``give_up_after_s``."""
    deadline = time.monotonic() + give_up_after_s
    pause = 0.2
    while True:
        try:
            return store.fail(claim.job.job_id, claim.lease_token, error)
        except StoreUnavailable as exc:
            if time.monotonic() + pause > deadline:
                log.error(
                    "job %s: could not record its failure (%s); the lease will lapse",
                    claim.job.job_id,
                    exc,
                )
                return False
            time.sleep(pause)
            pause = min(2 * pause, _MAX_PAUSE_S)


def commit_outcome(
    store: JobStore,
    claim: Claim,
    result: Mapping[str, Any],
    artifacts: Sequence[Artifact],
    give_up_after_s: float,
) -> bool:
    """Store the result and artifacts; True when they are committed."""
    job = claim.job
    deadline = time.monotonic() + give_up_after_s
    pause = 0.2
    while True:
        try:
            stored = store.complete(job.job_id, claim.lease_token, result, artifacts)
        except (TypeError, ValueError) as exc:  # e.g. a NaN in the result document
            log.exception("job %s produced an unstorable result", job.job_id)
            record_failure(store, claim, error_document(exc), give_up_after_s)
            return False
        except (StorageFull, StorageError) as exc:
            log.error("job %s: storage fault while storing results: %s", job.job_id, exc)
            record_failure(store, claim, _storage_failure(exc, job.attempts), give_up_after_s)
            return False
        except StoreUnavailable as exc:
            if time.monotonic() + pause > deadline:
                log.error(
                    "job %s: the store stayed unavailable (%s); the lease will lapse "
                    "and the job will be retried",
                    job.job_id,
                    exc,
                )
                return False
            log.warning(
                "job %s: store unavailable while storing results (%s); retrying", job.job_id, exc
            )
            time.sleep(pause)
            pause = min(2 * pause, _MAX_PAUSE_S)
            continue
        if not stored:
            log.warning("job %s: result discarded, the attempt no longer owns it", job.job_id)
        return stored
