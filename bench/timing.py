"""The timing helpers every bench uses (run a bench as ``python bench/<name>.py``, which
puts this folder on ``sys.path``).

- :func:`best_time`: the least wall time of ``repeat`` calls (the least is the run the
  machine disturbed least; the benches compare two implementations in one run);
- :func:`seconds_per_item`: the mean time per item of a slow reference loop, for
  implementations too slow to run on the whole input;
- :func:`percentile`: a latency percentile (nearest rank).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from typing import TypeVar

__all__ = ["best_time", "percentile", "seconds_per_item"]

T = TypeVar("T")


def best_time(run: Callable[[], object], repeat: int) -> float:
    """The least wall time (s) of ``repeat`` calls of ``run``."""
    times = []
    for _ in range(max(1, repeat)):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def seconds_per_item(run: Callable[[T], object], items: Iterable[T]) -> float:
    """Mean wall time (s) of ``run(item)`` over ``items`` (one pass)."""
    chosen = list(items)
    start = time.perf_counter()
    for item in chosen:
        run(item)
    return (time.perf_counter() - start) / max(1, len(chosen))


def percentile(values: Sequence[float], q: float) -> float:
    """The ``q`` quantile (0..1) of ``values`` by nearest rank."""
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]
