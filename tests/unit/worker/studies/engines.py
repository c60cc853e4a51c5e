"""The two engines of a design study side by side: a study's designs evaluated through
the process's kernel and by the process per design, compared design by design.

Feasibility must agree exactly; so must the reason code, and the field of a refusal,
except where a kernel's documented shortcut leaves a refusal unchecked because it
cannot change feasibility (``shortcuts``: (per-design field, batched code) pairs that
may stand for each other); each feasible design's objectives agree to 1e-12 relative.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from worker.registry import default_registry
from worker.studies.batched import evaluate_batched
from worker.studies.engine import choose_engine
from worker.studies.evaluation import chunk_rows, evaluate_block
from worker.studies.rows import FEASIBLE, ChunkRows
from worker.studies.spec import StudySpec

REGISTRY = default_registry()
RELATIVE = 1e-12


def both_engines(inputs: Mapping[str, Any]) -> tuple[ChunkRows, ChunkRows]:
    """(batched, per-design) rows of every design of the study ``inputs``."""
    spec = StudySpec.model_validate(inputs)
    process = REGISTRY.get(spec.process)
    assert process is not None
    choice = choose_engine(spec, process)
    assert choice.engine == "batched", choice.why
    count = spec.designs.count
    batched = evaluate_batched(spec, process, choice, 0, count)
    per_design = chunk_rows(evaluate_block(spec, process, 0, count), 0, count,
                            len(spec.objectives))  # fmt: skip
    return batched, per_design


def field(rows: ChunkRows, design: int) -> str:
    return rows.field_names[int(rows.fields[design])]


def assert_engines_agree(
    inputs: Mapping[str, Any], shortcuts: Iterable[tuple[str, int]] = ()
) -> tuple[ChunkRows, ChunkRows]:
    """Both engines over ``inputs``, checked as the module doc says; (batched, per-design)."""
    batched, per_design = both_engines(inputs)
    allowed = set(shortcuts)
    for n in range(len(batched.codes)):
        fast, slow = int(batched.codes[n]), int(per_design.codes[n])
        assert (fast == FEASIBLE) == (slow == FEASIBLE), (n, fast, slow, field(per_design, n))
        if fast != slow or field(batched, n) != field(per_design, n):
            assert (field(per_design, n), fast) in allowed, (
                n, fast, slow, field(batched, n), field(per_design, n),
                per_design.tally.counts,
            )  # fmt: skip
        if fast == FEASIBLE:
            for a, b in zip(batched.objectives[n].tolist(), per_design.objectives[n].tolist(),
                            strict=True):  # fmt: skip
                assert math.isclose(a, b, rel_tol=RELATIVE, abs_tol=0.0), (n, a, b)
        else:
            assert np.isnan(batched.objectives[n]).any()
    return batched, per_design
