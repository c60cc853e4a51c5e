"""The queue page's context: what waits and runs, per process; the workers and their
last heartbeat; how many jobs finished lately.

Every caller sees the totals (jobs queued and running per process, across owners,
study chunks included; how many workers are live; recent throughput, everyone's).  An admin also
sees every queued or running job and each worker (host, pid, last heartbeat); anyone
else sees only its own jobs, and of the workers only how many there are.

Recent throughput counts the client jobs (not study chunks) that finished in the last
``window_s`` seconds, looked for among those created in the last ``2 * window_s`` plus
the longest time limit of a process (a job created earlier has ended by then).
"""

from __future__ import annotations

from collections import Counter
from datetime import UTC, datetime, timedelta
from typing import Any

from service.documents import as_json, status_document
from service.pages.job_timing import duration_s, duration_text
from worker.contract import JobRecord, JobStatus
from worker.processes import ProcessRegistry
from worker.store.base import JobFilter, JobStore
from worker.store.records import WorkerInfo

__all__ = ["queue_context"]

#: Jobs listed on the page at most (the counts are complete).
_LISTED = 200
#: The listing page size while counting.
_PAGE = 1000
_UNFINISHED = frozenset({JobStatus.ACCEPTED, JobStatus.RUNNING})
_ENDED = frozenset({JobStatus.SUCCESSFUL, JobStatus.FAILED})


def _jobs(store: JobStore, where: JobFilter, owner: str | None, cap: int) -> list[JobRecord]:
    """Client jobs matching ``where`` (newest first), at most ``cap``."""
    found: list[JobRecord] = []
    cursor: str | None = None
    while len(found) < cap:
        page = store.list_jobs(limit=min(_PAGE, cap - len(found)), cursor=cursor, owner=owner,
                               where=where)  # fmt: skip
        found.extend(page.jobs)
        cursor = page.next_cursor
        if not cursor:
            break
    return found


def _per_process(depth: dict[tuple[str, JobStatus], int]) -> list[dict[str, Any]]:
    processes = sorted({p for p, _ in depth})
    return [
        {
            "process_id": p,
            "queued": depth.get((p, JobStatus.ACCEPTED), 0),
            "running": depth.get((p, JobStatus.RUNNING), 0),
        }
        for p in processes
    ]


def _worker(info: WorkerInfo, now: datetime) -> dict[str, Any]:
    beat = datetime.fromtimestamp(info.heartbeat, UTC)
    return {
        "worker_id": info.worker_id,
        "host": info.host,
        "pid": info.pid,
        "started": datetime.fromtimestamp(info.started, UTC).isoformat().replace("+00:00", "Z"),
        "heartbeat": beat.isoformat().replace("+00:00", "Z"),
        "heartbeat_ago": duration_text(max(0.0, (now - beat).total_seconds())),
    }


def _throughput(store: JobStore, registry: ProcessRegistry, owner: str | None, now: datetime,
                window_s: float) -> dict[str, Any]:  # fmt: skip
    longest = max((d.time_limit_s for d in registry), default=600.0)
    since = now - timedelta(seconds=window_s)
    where = JobFilter(statuses=_ENDED, created_from=since - timedelta(seconds=window_s + longest))
    ended = [
        j for j in _jobs(store, where, owner, 10 * _PAGE) if j.finished and j.finished >= since
    ]
    took = [d for d in (duration_s(j, now) for j in ended) if d is not None]
    return {
        "window": duration_text(window_s),
        "finished": len(ended),
        "failed": sum(1 for j in ended if j.status is JobStatus.FAILED),
        "per_minute": f"{len(ended) / (window_s / 60):.2g}",
        "mean_duration": duration_text(sum(took) / len(took)) if took else "",
    }


def queue_context(store: JobStore, registry: ProcessRegistry, *, owner: str | None,
                  admin: bool, live_within_s: float, window_s: float = 3600.0,
                  now: datetime | None = None) -> dict[str, Any]:  # fmt: skip
    """The queue page's context for a caller whose jobs are ``owner``'s (None: an
    admin, every owner's)."""
    now = now or datetime.now(UTC)
    depth = store.queue_depth()
    workers = store.live_workers(within_s=live_within_s)
    waiting = _jobs(store, JobFilter(statuses=_UNFINISHED), owner, _LISTED)
    mine = Counter((j.process_id, j.status) for j in waiting)
    rows = _per_process(depth)
    for row in rows:
        row["mine_queued"] = mine.get((row["process_id"], JobStatus.ACCEPTED), 0)
        row["mine_running"] = mine.get((row["process_id"], JobStatus.RUNNING), 0)
    return {
        "admin": admin,
        "per_process": rows,
        "total_queued": sum(r["queued"] for r in rows),
        "total_running": sum(r["running"] for r in rows),
        "jobs": [
            {**as_json(status_document(j)), "duration": duration_text(duration_s(j, now))}
            for j in waiting
        ],
        "jobs_capped": len(waiting) >= _LISTED,
        "worker_count": len(workers),
        "workers": [_worker(w, now) for w in workers] if admin else [],
        "throughput": _throughput(store, registry, None, now, window_s),  # a total
        "live_within": duration_text(live_within_s),
    }
