"""A design study of 10^6 SPM designs on a real `dexlab serve` with two worker processes:
it is accepted with the default limits, runs through the kernel to ``successful``, and
the worker processes stay under 1 GB and the API under 300 MB (peak resident memory,
VmHWM, read from /proc while it runs).  The wall time and the memory are printed
(``-s``) and recorded as test properties.

A benchmark (several minutes on the 2-core test machine): skipped unless
``DEXLAB_BENCH=1``::

    DEXLAB_BENCH=1 .venv/bin/python -m pytest tests/integration/test_million_designs.py -s
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import deployment, wait_terminal
from worker.studies.examples import STUDY_EXAMPLES

pytestmark = [
    pytest.mark.integration,
    pytest.mark.bench,
    pytest.mark.skipif(os.environ.get("DEXLAB_BENCH") != "1", reason="a benchmark: DEXLAB_BENCH=1"),
]

URL = "/v1/processes/design-study/execution"
SIDE = 1000
#: The first worked SPM study (Bai's Example I) on a 1000 x 1000 grid of (alpha1, alpha2).
MILLION: dict[str, Any] = {
    **dict(STUDY_EXAMPLES[0].inputs),
    "vary": {"alpha1_deg": [30, 150, SIDE], "alpha2_deg": [30, 150, SIDE]},
}
WORKER_BYTES = 1 << 30
API_BYTES = 300 << 20


def peak_bytes(pid: int) -> int:
    """A process's peak resident memory (VmHWM), 0 once it is gone."""
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def descendants(pid: int) -> list[int]:
    """Every process below ``pid`` (its worker pool, their helpers)."""
    found, todo = [], [pid]
    while todo:
        parent = todo.pop()
        try:
            with open(f"/proc/{parent}/task/{parent}/children") as handle:
                children = [int(c) for c in handle.read().split()]
        except OSError:
            children = []
        found += children
        todo += children
    return found


class PeakWatch:
    """Samples the peaks of the API process and of every process below it."""

    def __init__(self, api_pid: int) -> None:
        self.api_pid = api_pid
        self.api = 0
        self.workers: dict[int, int] = {}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            self.sample()
            self._stop.wait(1.0)

    def sample(self) -> None:
        self.api = max(self.api, peak_bytes(self.api_pid))
        for pid in descendants(self.api_pid):
            self.workers[pid] = max(self.workers.get(pid, 0), peak_bytes(pid))

    def __enter__(self) -> PeakWatch:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()
        self.sample()


def test_a_million_designs_in_minutes_with_bounded_memory(
    tmp_path: Path, record_property: Callable[[str, object], None]
) -> None:
    with deployment("embedded", tmp_path, workers=2) as dep:
        assert dep.api is not None
        client = dep.client
        with PeakWatch(dep.api.pid) as peaks:
            start = time.perf_counter()
            submitted = client.post(URL, json={"inputs": MILLION})
            assert submitted.status_code == 201, submitted.text
            study_id = submitted.json()["jobID"]
            done = wait_terminal(client, study_id, timeout=1800)
            wall = time.perf_counter() - start
            assert done["status"] == "successful", (done, dep.log())
            result = client.get(f"/v1/jobs/{study_id}/results").json()["result"]
            with client.stream("GET", f"/v1/jobs/{study_id}/results/designs.csv") as response:
                csv_bytes = sum(len(chunk) for chunk in response.iter_bytes())
        assert result["engine"] == "batched"
        assert result["count"] == result["evaluated"] == SIDE * SIDE
        assert 0 < result["feasible"] < SIDE * SIDE and result["pareto_size"] > 0
        assert csv_bytes > 30 * SIDE * SIDE
        worker = max(peaks.workers.values())
        load = os.getloadavg()[0]
        line = (f"10^6 SPM designs: {wall:.1f} s end to end, {result['chunks']} chunks, "
                f"{result['feasible']:,} feasible; peak RSS: API {peaks.api / 2**20:.0f} MB, "
                f"worker processes {worker / 2**20:.0f} MB; load {load:.1f}")  # fmt: skip
        print(line)
        for name, value in (("wall_s", round(wall, 1)), ("api_mb", peaks.api >> 20),
                            ("worker_mb", worker >> 20), ("chunks", result["chunks"])):  # fmt: skip
            record_property(name, value)
        assert peaks.api < API_BYTES, line
        assert worker < WORKER_BYTES, line
