"""Validated inputs of ``design-study``: which process, over which designs, judged how.

``process`` is any single-design process of the registry the study belongs to (the
model :func:`study_spec_for` makes for it checks that); ``fixed`` holds its other inputs
exactly as it takes them; ``vary`` (a grid, ``{"path": [lo, hi, n]}``) or ``sample``
(Sobol or Latin hypercube over ``bounds``) says which inputs change; ``objectives``
maps result paths (:mod:`.paths`) to ``"max"`` or ``"min"``.  Checks that need the
target process itself (a design it refuses, an objective it does not report) are made
on the first design at submission, not here.

Every refusal names its place: ``vary.links[0]``, ``sample.bounds.alpha1_deg``,
``objectives.optimum.eta``.  A varied path must have a place in
``fixed`` (a key may be created, a list element must be there), apart from the other
varied paths and from what ``fixed`` gives: checked here, once, so that every design's
inputs can be built.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Annotated, Any, Literal

from pydantic import (
    BeforeValidator,
    Field,
    JsonValue,
    create_model,
    field_validator,
    model_validator,
)

from worker.common.field_errors import field_error
from worker.common.specs import FrozenSpec
from worker.studies.designs import GridSpace, SampleSpace
from worker.studies.paths import (
    InputPath,
    parse_input_path,
    parse_result_path,
    varied_input_problem,
)

__all__ = ["MAX_DESIGNS", "MAX_OBJECTIVES", "SampleSpec", "StudySpec", "study_spec_for"]

#: Most designs one study may hold (the cost model may refuse fewer).
MAX_DESIGNS = 1_000_000
MAX_OBJECTIVES = 3
MAX_VARIED = 6
#: Most designs one chunk may hold (a batched chunk of a cheap kernel holds many).
MAX_CHUNK = MAX_DESIGNS
#: Processes a study cannot evaluate: itself and its own chunks.
NOT_STUDIED = frozenset({"design-study", "design-study-chunk"})


def _finite(value: Any) -> bool:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return False
    try:
        return math.isfinite(float(value))
    except OverflowError:  # an integer beyond any float
        return False


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else f"{text[:57]}..."


def _range(value: Any, what: str, count: bool) -> Any:
    """``value`` if it is ``[lo, hi]`` (``[lo, hi, n]`` with ``count``): finite numbers
    lo <= hi whose difference is finite too, n a whole number from 1; else ValueError."""
    size = 3 if count else 2
    if not isinstance(value, list | tuple) or len(value) != size:
        raise ValueError(f"{what}, not {_shown(value)}")
    lo, hi = value[0], value[1]
    if not (_finite(lo) and _finite(hi)):
        raise ValueError(f"{what}: lo and hi must be finite numbers, not {_shown(value)}")
    if lo > hi:
        raise ValueError(f"{what}: lo {lo:g} exceeds hi {hi:g} (it needs lo <= hi)")
    if not math.isfinite(float(hi) - float(lo)):
        raise ValueError(f"{what}: hi - lo = {hi:g} - ({lo:g}) is beyond a float")
    if count:
        n = value[2]
        whole = _finite(n) and float(n).is_integer() and not isinstance(n, bool)
        if not whole or not 1 <= n <= MAX_DESIGNS:
            raise ValueError(f"{what}: n (how many values) must be a whole number from 1 to "
                             f"{MAX_DESIGNS:,}, not {_shown(n)}")  # fmt: skip
    return value


GridAxis = Annotated[
    tuple[float, float, int],
    BeforeValidator(lambda v: _range(v, "a varied input is [lo, hi, n]", count=True)),
]
Bound = Annotated[
    tuple[float, float], BeforeValidator(lambda v: _range(v, "a bound is [lo, hi]", count=False))
]


def _checked_paths(model: type[FrozenSpec], names: Mapping[str, Any]) -> None:
    """Each name an input path, or a field error at that name."""
    for name, value in names.items():
        try:
            parse_input_path(name)
        except ValueError as exc:
            raise field_error(model, (name,), str(exc), value) from None


class SampleSpec(FrozenSpec):
    """A seeded low-discrepancy sample of ``count`` designs within ``bounds``."""

    method: Literal["sobol", "latin_hypercube"] = Field(
        "sobol", description="'sobol' (scrambled) or 'latin_hypercube'."
    )
    count: int = Field(..., ge=1, le=MAX_DESIGNS, description=f"Designs, 1..{MAX_DESIGNS:,}.")
    bounds: dict[str, Bound] = Field(
        ...,
        min_length=1,
        max_length=MAX_VARIED,
        description="Input path -> [lo, hi] (lo <= hi), e.g. {'alpha1_deg': [30, 150]}.",
    )
    seed: int = Field(0, ge=0, le=2**32 - 1, description="Seed: same seed, same designs.")

    @field_validator("bounds")
    @classmethod
    def _paths(cls, bounds: dict[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
        _checked_paths(cls, bounds)
        return bounds


class StudySpec(FrozenSpec):
    """Inputs of ``design-study``."""

    # ``process`` is checked by the model study_spec_for makes for a registry (the
    # docstring above is the published schema's description).

    process: str = Field(..., description="The process evaluated for every design.")
    fixed: dict[str, JsonValue] = Field(
        default_factory=dict,
        description="The process's other inputs, exactly as it takes them.",
    )
    vary: dict[str, GridAxis] | None = Field(
        None,
        min_length=1,
        max_length=MAX_VARIED,
        description="A grid: input path -> [lo, hi, n] (n >= 1 values from lo to hi). "
        "Not with 'sample'.",
    )
    sample: SampleSpec | None = Field(None, description="A sample instead of a grid.")
    objectives: dict[str, Literal["max", "min"]] = Field(
        ...,
        min_length=1,
        max_length=MAX_OBJECTIVES,
        description="Result path -> 'max' or 'min', e.g. {'optimum.eta': 'max', "
        "'task_points[].d_z|min': 'max'}; a list reduced with |min, |max, |mean or |sum.",
    )
    chunk_size: int | None = Field(
        None,
        ge=1,
        le=MAX_CHUNK,
        description="Designs per chunk job (default: about a second of work per chunk).",
    )
    allow_partial: bool = Field(
        False,
        description="A chunk that fails after its attempts: report its designs as missing "
        "instead of failing the study.",
    )
    engine: Literal["auto", "batched", "per-design"] = Field(
        "auto",
        description="How the designs are evaluated: 'batched' through the process's study "
        "kernel (many designs at once, the same numbers; its result paths say "
        "\"kernel\": true), 'per-design' by running the whole process once per design (the "
        "reference), or 'auto' (the default): batched whenever the kernel covers every "
        "objective and every varied input. 'batched' is refused when it cannot be.",
    )
    best_count: int = Field(5, ge=1, le=100, description="Best designs listed per objective.")
    plots: bool = Field(True, description="Render the study's plots (PNG/SVG).")

    @field_validator("vary")
    @classmethod
    def _grid(cls, vary: dict[str, tuple[float, float, int]] | None) -> Any:
        if vary is not None:
            _checked_paths(cls, vary)
        return vary

    @field_validator("objectives")
    @classmethod
    def _objective_paths(cls, objectives: dict[str, str]) -> dict[str, str]:
        for name, direction in objectives.items():
            try:
                parse_result_path(name)
            except ValueError as exc:
                raise field_error(cls, (name,), str(exc), direction) from None
        return objectives

    @model_validator(mode="after")
    def _one_design_set(self) -> StudySpec:
        if self.vary is None and self.sample is None:
            raise field_error(self, "vary", "give exactly one of 'vary' (a grid) and "
                              "'sample'", None)  # fmt: skip
        if self.vary is not None and self.sample is not None:
            raise field_error(self, "sample", "give exactly one of 'vary' (a grid) and "
                              "'sample', not both", None)  # fmt: skip
        space = self.designs
        if space.count > MAX_DESIGNS:
            raise field_error(self, "vary", f"the grid holds {space.count:,} designs, more "
                              f"than {MAX_DESIGNS:,}", self.vary)  # fmt: skip
        where = ("vary",) if self.vary is not None else ("sample", "bounds")
        earlier: dict[str, InputPath] = {}
        for name in space.names:
            path = parse_input_path(name)
            problem = varied_input_problem(self.fixed, path, earlier)
            if problem is not None:
                raise field_error(self, (*where, name), problem, name)
            earlier[name] = path
        return self

    @property
    def designs(self) -> GridSpace | SampleSpace:
        if self.vary is not None:
            axes = tuple((name, lo, hi, n) for name, (lo, hi, n) in self.vary.items())
            return GridSpace(axes)
        assert self.sample is not None
        bounds = tuple((name, lo, hi) for name, (lo, hi) in self.sample.bounds.items())
        return SampleSpace(self.sample.method, bounds, self.sample.count, self.sample.seed)


def study_spec_for(process_ids: Iterable[str]) -> type[StudySpec]:
    """The inputs model of a study of one of ``process_ids`` (its registry's: the study's
    own processes are left out), named ``StudySpec`` like the model it extends."""
    ids = [pid for pid in process_ids if pid not in NOT_STUDIED]

    def known(cls: type[StudySpec], process: str) -> str:
        if process not in ids:
            raise ValueError(
                f"{process!r} is not a process a study can run; one of {', '.join(ids)}"
            )
        return process

    return create_model(
        "StudySpec",
        __base__=StudySpec,
        __module__=__name__,
        __doc__=StudySpec.__doc__,
        __validators__={"_known": field_validator("process")(classmethod(known))},  # type: ignore[dict-item]
    )
