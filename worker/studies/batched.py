"""Evaluating a block of a study's designs through the process's study kernel.

The kernel (:mod:`worker.study_kernels`) answers, for many designs at once, the numbers
at the declared paths the objectives read and the refusals that depend on the varied
values; here each objective is read from them as :func:`~.paths.read_result` reads a
result document (an index selects, ``[]`` keeps every element, a reduction flattens;
a non-finite number is no value; a sum and a mean are exactly rounded), a design the
process would refuse for its cost (the template's, the same for every design) is
refused, and every design gets its reason code (:mod:`.rows`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray

from worker.input_validation import field_path
from worker.processes import ProcessDefinition
from worker.result_paths import declared_steps
from worker.studies.engine import EngineChoice
from worker.studies.files import objective_entry
from worker.studies.paths import ResultPath, parse_result_path
from worker.studies.rows import FEASIBLE, NO_VALUE, REFUSED, ChunkRows, ReasonTally
from worker.studies.spec import StudySpec
from worker.study_kernels import KernelBlock

__all__ = ["BATCH", "evaluate_batched", "objective_column"]

#: Designs handed to a kernel at once (it tiles its own work within them).
BATCH = 16_384
FloatArray = NDArray[np.float64]


def _exact_sums(rows: FloatArray) -> FloatArray:
    """Each row's exactly rounded sum (:func:`math.fsum`, as a result is read)."""
    if rows.shape[1] == 1:
        return rows[:, 0].copy()
    return np.fromiter(map(math.fsum, rows.tolist()), dtype=np.float64, count=len(rows))


def objective_column(values: FloatArray, declared: str, path: ResultPath) -> FloatArray:
    """One objective ``(m,)`` (NaN: no value) from a kernel's array ``(m, *L)`` at the
    declared path ``declared`` that ``path`` reads."""
    steps = declared_steps(declared)
    given = (*path.steps, None) if len(path.steps) < len(steps) else path.steps
    arr = np.where(np.isfinite(values), values, np.nan)
    axis = 1
    for step, part in zip(steps, given, strict=True):
        if step is not None:
            continue
        if isinstance(part, int):
            if part >= arr.shape[axis]:
                arr = np.take(arr, np.arange(0), axis=axis)
                axis += 1
            else:
                arr = np.take(arr, part, axis=axis)
        else:
            axis += 1
    m = arr.shape[0]
    flat = arr.reshape(m, -1)
    if path.reduction is None:
        return flat[:, 0] if flat.shape[1] == 1 else np.full(m, np.nan)
    if flat.shape[1] == 0:
        return np.zeros(m) if path.reduction == "sum" else np.full(m, np.nan)
    absent = np.asarray(np.isnan(flat).any(axis=1), dtype=bool)
    if path.reduction == "min":
        reduced = flat.min(axis=1)
    elif path.reduction == "max":
        reduced = flat.max(axis=1)
    else:
        reduced = _exact_sums(np.where(absent[:, None], 0.0, flat))
        if path.reduction == "mean":
            reduced = reduced / flat.shape[1]
    return np.where(absent, np.nan, reduced)


def _objectives(
    block: KernelBlock, declared: Sequence[str], paths: Sequence[ResultPath]
) -> FloatArray:
    pairs = zip(declared, paths, strict=True)
    columns = [objective_column(block.values[d], d, p) for d, p in pairs]
    return np.stack(columns, axis=1) if columns else np.zeros((len(block.refused), 0))


def evaluate_batched(
    spec: StudySpec,
    process: ProcessDefinition,
    choice: EngineChoice,
    start: int,
    stop: int,
    on_design: Callable[[int, int], None] | None = None,
) -> ChunkRows:
    """Rows of the designs ``start`` to ``stop`` (exclusive), through the kernel."""

    assert choice.plan is not None
    names = list(spec.objectives)
    paths = [parse_result_path(name) for name in names]
    declared = []
    for name in names:
        entry = objective_entry(process, name)
        assert entry is not None  # the engine's choice checked it
        declared.append(entry.path)
    count = stop - start
    objectives = np.full((count, len(names)), np.nan)
    codes = np.zeros(count, dtype=np.int8)
    fields = np.zeros(count, dtype=np.int16)
    field_names: list[str] = [""]
    tally = ReasonTally()
    over_limit = choice.template_cost > process.cost_limit
    for first in range(0, count, BATCH):
        last = min(first + BATCH, count)
        with np.errstate(all="ignore"):  # a design out of range is the kernel's to refuse
            block = choice.plan.evaluate(spec.designs.block(start + first, start + last))
        values = _objectives(block, declared, paths)
        refused = np.asarray(block.refused)
        for k, refusal in enumerate(block.refusals):
            rows = np.flatnonzero(refused == k)
            if rows.size:
                field = field_path(("inputs", *refusal.loc))
                if field not in field_names:
                    field_names.append(field)
                codes[first + rows] = REFUSED
                fields[first + rows] = field_names.index(field)
                tally.add(REFUSED, field, f"refused: Invalid value for '{field}': "
                          f"{refusal.message}", int(rows.size))  # fmt: skip
        accepted = refused < 0
        if over_limit and accepted.any():
            if "inputs" not in field_names:
                field_names.append("inputs")
            rows = np.flatnonzero(accepted)
            codes[first + rows] = REFUSED
            fields[first + rows] = field_names.index("inputs")
            costs = f"costs {choice.template_cost:,} {process.cost_unit}"
            tally.add(REFUSED, "inputs", f"refused: {costs}, above {process.cost_limit:,}",
                      int(rows.size))  # fmt: skip
            accepted[:] = False
        objectives[first:last][accepted] = values[accepted]
        _no_values(values, accepted, names, codes[first:last], tally)
        if on_design is not None:
            on_design(last, count)
    return ChunkRows(start, stop, objectives, codes, fields, tuple(field_names), tally,
                     "batched")  # fmt: skip


def _no_values(
    values: FloatArray, accepted: NDArray[np.bool_], names: Sequence[str],
    codes: NDArray[np.int8], tally: ReasonTally,
) -> None:  # fmt: skip
    """Accepted designs without a value for some objective: ``no-value``, counted by
    which objectives lack one."""
    absent = np.isnan(values) & accepted[:, None]
    lacking = absent.any(axis=1)
    codes[lacking] = NO_VALUE
    codes[accepted & ~lacking] = FEASIBLE
    if not lacking.any():
        return
    patterns, counts = np.unique(absent[lacking], axis=0, return_counts=True)
    for pattern, designs in zip(patterns.tolist(), counts.tolist(), strict=True):
        missing = ", ".join(n for n, gone in zip(names, pattern, strict=True) if gone)
        tally.add(NO_VALUE, "", f"no value for {missing}", int(designs))
