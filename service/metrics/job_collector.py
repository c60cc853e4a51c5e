"""The job figures of ``/metrics``, read from the job store at each scrape.

The store holds every figure (:mod:`worker.store.tallies`: running counts added to in
the transaction of each job event; the queue and the worker registry), so they are
right whichever process or machine ran the jobs: spawned pool processes, Celery
workers elsewhere, other API replicas.  A scrape is three small queries; when the
store does not answer, ``dexlab_store_up`` is 0 and the job families are left out.
"""

from __future__ import annotations

import logging
import math
from collections import defaultdict
from collections.abc import Iterable, Iterator, Sequence

from prometheus_client.core import (
    CounterMetricFamily,
    GaugeMetricFamily,
    HistogramMetricFamily,
    Metric,
)
from prometheus_client.registry import Collector

from worker.contract import JobStatus
from worker.errors import StoreUnavailable
from worker.store.base import JobStore, JobTally, WorkerInfo
from worker.store.tallies import DURATION_BUCKETS, QUEUE_WAIT_BUCKETS, bound_label, label_bound

__all__ = ["JobStoreCollector"]

log = logging.getLogger("dexlab.metrics")

#: The statuses a job finishes in, as the API writes them.
FINISHED = (JobStatus.SUCCESSFUL, JobStatus.FAILED, JobStatus.DISMISSED)
#: The statuses of the queue: waiting, and being run.
QUEUED = (JobStatus.ACCEPTED, JobStatus.RUNNING)

_COUNTERS = {
    "submitted": ("dexlab_jobs_submitted", "Jobs submitted."),
    "reused": ("dexlab_jobs_reused", "Jobs answered at once by a stored result (reuse)."),
    "attempts": ("dexlab_job_attempts", "Attempts started (a claim by a worker)."),
    "retries": ("dexlab_job_retries", "Attempts after a job's first (its worker was lost)."),
}
_HISTOGRAMS = {
    "duration": (
        "dexlab_job_duration_seconds",
        "From a job's first start to its finish, for jobs that finished successful or failed.",
        DURATION_BUCKETS,
    ),
    "queue_wait": (
        "dexlab_job_queue_wait_seconds",
        "From a job's submission to its first start.",
        QUEUE_WAIT_BUCKETS,
    ),
}


class _Figures:
    """One scrape's tallies, by (process, tally) -> label -> tally."""

    def __init__(self, tallies: Iterable[JobTally]) -> None:
        self.rows: dict[tuple[str, str], dict[str, JobTally]] = defaultdict(dict)
        for tally in tallies:
            self.rows[(tally.process_id, tally.tally)][tally.label] = tally

    def processes(self) -> set[str]:
        return {process for process, _ in self.rows}

    def count(self, process: str, tally: str, label: str = "") -> int:
        found = self.rows.get((process, tally), {}).get(label)
        return 0 if found is None else found.count

    def buckets(
        self, process: str, tally: str, bounds: Sequence[float]
    ) -> tuple[list[tuple[str, float]], float]:
        """Cumulative ``(le, count)`` pairs ending with ``+Inf``, and the sum."""
        stored = self.rows.get((process, tally), {}).values()
        observed = [(label_bound(t.label), t.count) for t in stored]
        cumulative = [
            (bound_label(bound), float(sum(n for at, n in observed if at <= bound)))
            for bound in (*bounds, math.inf)
        ]
        return cumulative, float(sum(t.total for t in stored))


class JobStoreCollector(Collector):
    """Job counts, histograms, the queue and the live workers, from ``store``.

    ``process_ids`` (the registered processes) always appear, with zeros until their
    first job; ``live_within_s`` is how recent a worker's heartbeat must be (as for
    ``/health/ready``)."""

    def __init__(self, store: JobStore, process_ids: Iterable[str], live_within_s: float) -> None:
        self._store = store
        self._process_ids = frozenset(process_ids)
        self._live_within_s = live_within_s

    def describe(self) -> Iterable[Metric]:
        """The families, without reading the store (registration must not)."""
        return list(self._families(_Figures(()), {}, [], store_up=True))

    def collect(self) -> Iterable[Metric]:
        try:
            tallies = self._store.job_tallies()
            depth = self._store.queue_depth()
            workers = self._store.live_workers(within_s=self._live_within_s)
        except StoreUnavailable as exc:
            log.warning("metrics: the job store did not answer (%s)", exc)
            return [_store_up(False)]
        return list(self._families(_Figures(tallies), depth, workers, store_up=True))

    def _families(
        self,
        figures: _Figures,
        depth: dict[tuple[str, JobStatus], int],
        workers: list[WorkerInfo],
        *,
        store_up: bool,
    ) -> Iterator[Metric]:
        processes = sorted(self._process_ids | figures.processes() | {p for p, _ in depth})
        yield _store_up(store_up)
        for tally, (name, documentation) in _COUNTERS.items():
            counter = CounterMetricFamily(name, documentation, labels=["process"])
            for process in processes:
                counter.add_metric([process], figures.count(process, tally))
            yield counter
        finished = CounterMetricFamily(
            "dexlab_jobs_finished",
            "Jobs that finished, by the status they finished in (dismissed: before "
            "finishing otherwise).",
            labels=["process", "status"],
        )
        for process in processes:
            for status in FINISHED:
                finished.add_metric([process, status.value],
                                    figures.count(process, "finished", status.value))  # fmt: skip
        yield finished
        for tally, (name, documentation, bounds) in _HISTOGRAMS.items():
            histogram = HistogramMetricFamily(name, documentation, labels=["process"])
            for process in processes:
                buckets, total = figures.buckets(process, tally, bounds)
                histogram.add_metric([process], buckets, total)
            yield histogram
        queue = GaugeMetricFamily(
            "dexlab_queue_depth",
            "Jobs waiting (accepted) and being run (running), now.",
            labels=["process", "status"],
        )
        for process in processes:
            for status in QUEUED:
                queue.add_metric([process, status.value], depth.get((process, status), 0))
        yield queue
        yield GaugeMetricFamily(
            "dexlab_workers_live",
            "Worker processes (local pool) or Celery worker nodes whose heartbeat is recent.",
            value=len(workers),
        )


def _store_up(up: bool) -> GaugeMetricFamily:
    return GaugeMetricFamily(
        "dexlab_store_up", "1 if the job store answered this scrape, else 0.", value=1 if up else 0
    )
