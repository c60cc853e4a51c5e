"""How a study cuts its designs into chunk jobs of about a second of work each.

A batched study (:mod:`.engine`) sizes its chunks by the cost model alone: a design
costs the kernel's ``plan.cost`` (in the process's cost unit) times the kernel's
measured ``seconds_per_cost``, plus the study's own bookkeeping per design, so a
re-run of the same inputs splits the same way.  A per-design study (the reference
engine) times its first design (twice, the faster run counted): a single-design run's
time is not something a cost unit says.  Either way there are at least
:data:`MIN_CHUNKS` chunks when there are that many designs, none above
:data:`~.spec.MAX_CHUNK`, and ``chunk_size`` overrides.
"""

from __future__ import annotations

import math
import time
from typing import Any

from worker.processes import ProcessDefinition
from worker.studies.engine import EngineChoice, choose_engine
from worker.studies.evaluation import evaluate_block
from worker.studies.spec import MAX_CHUNK, StudySpec

__all__ = ["CHUNK_SECONDS", "MIN_CHUNKS", "chunk_inputs", "chunk_size", "design_seconds"]

#: Aimed-for work per chunk (seconds), and the least number of chunks of a study.
CHUNK_SECONDS = 1.0
MIN_CHUNKS = 4
#: A batched design's share of the study's own work (reading objectives, reason
#: codes, storing and assembling its row), in seconds.
STUDY_SECONDS_PER_DESIGN = 3e-6


def design_seconds(choice: EngineChoice) -> float:
    """A batched design's seconds by the cost model."""
    assert choice.kernel is not None and choice.plan is not None
    return choice.plan.cost * choice.kernel.seconds_per_cost + STUDY_SECONDS_PER_DESIGN


def _timed_seconds(spec: StudySpec, process: ProcessDefinition) -> float:
    seconds = math.inf
    for _ in range(2):  # the first run may pay for imports and caches: the faster counts
        start = time.perf_counter()
        evaluate_block(spec, process, 0, 1)
        seconds = min(seconds, max(time.perf_counter() - start, 1e-4))
    return seconds


def chunk_size(spec: StudySpec, process: ProcessDefinition, choice: EngineChoice) -> int:
    """Designs per chunk (see the module doc)."""
    if spec.chunk_size is not None:
        return spec.chunk_size
    if choice.engine == "batched":
        seconds = design_seconds(choice)
    else:
        seconds = _timed_seconds(spec, process)
    count = spec.designs.count
    size = math.ceil(CHUNK_SECONDS / seconds)
    return max(1, min(size, math.ceil(count / MIN_CHUNKS), MAX_CHUNK))


def chunk_inputs(spec: StudySpec, process: ProcessDefinition) -> list[dict[str, Any]]:
    """The chunks' inputs: the study of ``process``, each block of designs in order,
    and the engine."""
    choice = choose_engine(spec, process)
    size = chunk_size(spec, process, choice)
    study = spec.model_dump(mode="json")
    count = spec.designs.count
    return [
        {"study": study, "start": start, "stop": min(start + size, count),
         "engine": choice.engine}
        for start in range(0, count, size)
    ]  # fmt: skip
