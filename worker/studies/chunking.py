"""How a study cuts its designs into chunk jobs of about a second of work each.

Chunks are sized by the cost model alone, never by timing a design, so a re-run of the
same inputs splits the same way.  A batched study (:mod:`.engine`): a design costs the
kernel's ``plan.cost`` (in the process's cost unit) times the kernel's measured
``seconds_per_cost``, plus the study's own bookkeeping per design.  A per-design study
(the reference engine): a design costs a job of the process
(:attr:`~worker.processes.ProcessDefinition.seconds_per_run` plus its ``cost`` times
:attr:`~worker.processes.ProcessDefinition.seconds_per_cost`), priced on the first
design the process accepts among a few spread over the space (the first may be refused
for its varied values), plus the study's validation of each design.  Either way there
are at least :data:`MIN_CHUNKS` chunks when there are that many designs, none above
:data:`~.spec.MAX_CHUNK`, and ``chunk_size`` overrides.
"""

from __future__ import annotations

import math
from typing import Any

from worker.errors import InvalidInputs
from worker.input_validation import validate_inputs
from worker.processes import ProcessDefinition
from worker.studies.engine import EngineChoice, choose_engine
from worker.studies.evaluation import design_inputs
from worker.studies.spec import MAX_CHUNK, StudySpec

__all__ = [
    "CHUNK_SECONDS",
    "MIN_CHUNKS",
    "chunk_inputs",
    "chunk_size",
    "design_seconds",
    "per_design_seconds",
    "probe_costs",
    "probe_indices",
]

#: Aimed-for work per chunk (seconds), and the least number of chunks of a study.
CHUNK_SECONDS = 1.0
MIN_CHUNKS = 4
#: A batched design's share of the study's own work (reading objectives, reason
#: codes, storing and assembling its row), in seconds.
STUDY_SECONDS_PER_DESIGN = 3e-6
#: A per-design study's own work per design (validating its inputs by the process's
#: model and published schema, reading its objectives), in seconds.
VALIDATION_SECONDS_PER_DESIGN = 2e-3
#: Designs tried, spread over the space, for one the process accepts to price.
PRICED_PROBES = 9


def design_seconds(choice: EngineChoice) -> float:
    """A batched design's seconds by the cost model."""
    assert choice.kernel is not None and choice.plan is not None
    return choice.plan.cost * choice.kernel.seconds_per_cost + STUDY_SECONDS_PER_DESIGN


def probe_indices(count: int, most: int = PRICED_PROBES) -> list[int]:
    """Designs a study tries for one its process accepts (at submission, and to price
    a per-design study), in order: the first, then evenly spread ones, the middle among
    them, then the last."""
    if count <= most:
        return list(range(count))
    spread = [round(i * (count - 1) / (most - 1)) for i in range(most)]
    return list(dict.fromkeys([0, count // 2, *spread]))


def probe_costs(spec: StudySpec, process: ProcessDefinition) -> list[float]:
    """The cost of a job of ``process`` (figures off, as a chunk runs it) on each design
    of :func:`probe_indices` the process accepts, in that order ([] when it refuses
    every one tried)."""
    costs: list[float] = []
    for index in probe_indices(spec.designs.count):
        design = tuple(float(v) for v in spec.designs.block(index, index + 1)[0])
        raw = design_inputs(spec, design)
        if "plots" in process.inputs_model.model_fields:
            raw["plots"] = False
        try:
            costs.append(float(process.cost(validate_inputs(process, raw))))
        except (InvalidInputs, ValueError):
            continue
    return costs


def per_design_seconds(spec: StudySpec, process: ProcessDefinition) -> float:
    """A per-design study's seconds per design by the cost model: a job of ``process``
    on the first accepted design among :func:`probe_indices` (just the fixed cost of a
    job when every one tried is refused), plus the study's validation."""
    costs = probe_costs(spec, process)
    cost = costs[0] if costs else 0.0
    return process.seconds_per_run + cost * process.seconds_per_cost + VALIDATION_SECONDS_PER_DESIGN


def chunk_size(spec: StudySpec, process: ProcessDefinition, choice: EngineChoice) -> int:
    """Designs per chunk (see the module doc)."""
    if spec.chunk_size is not None:
        return spec.chunk_size
    if choice.engine == "batched":
        seconds = design_seconds(choice)
    else:
        seconds = per_design_seconds(spec, process)
    count = spec.designs.count
    size = math.ceil(CHUNK_SECONDS / seconds)
    return max(1, min(size, math.ceil(count / MIN_CHUNKS), MAX_CHUNK))


def chunk_inputs(spec: StudySpec, process: ProcessDefinition) -> list[dict[str, Any]]:
    """The chunks' inputs: the study of ``process``, each block of designs in order,
    and the engine."""
    choice = choose_engine(spec, process)
    size = chunk_size(spec, process, choice)
    # chunk_size only cuts the work: a chunk's inputs (and so its result key) leave it
    # out, and a chunk of the same designs is reused whatever cut the study asked for
    study = spec.model_dump(mode="json", exclude={"chunk_size"})
    count = spec.designs.count
    return [
        {"study": study, "start": start, "stop": min(start + size, count),
         "engine": choice.engine}
        for start in range(0, count, size)
    ]  # fmt: skip
