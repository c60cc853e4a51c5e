"""Validated inputs of ``design-study``: which process, over which designs, judged how.

``process`` is any registered single-design process; ``fixed`` holds its other inputs
exactly as it takes them; ``vary`` (a grid, ``{"path": [lo, hi, n]}``) or ``sample``
(Sobol or Latin hypercube over ``bounds``) says which inputs change; ``objectives``
maps result paths (:mod:`.paths`) to ``"max"`` or ``"min"``.  Checks that need the
target process itself (a design it refuses, an objective it does not report) are made
on the first design at submission, not here.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, JsonValue, field_validator, model_validator

from worker.common.specs import FrozenSpec, entries
from worker.studies.designs import GridSpace, SampleSpace
from worker.studies.paths import parse_input_path, parse_result_path

__all__ = ["MAX_DESIGNS", "MAX_OBJECTIVES", "SampleSpec", "StudySpec"]

#: Most designs one study may hold (the cost model may refuse fewer).
MAX_DESIGNS = 1_000_000
MAX_OBJECTIVES = 3
MAX_VARIED = 6
MAX_CHUNK = 100_000
#: Processes a study cannot evaluate: itself and its own chunks.
NOT_STUDIED = frozenset({"design-study", "design-study-chunk"})


GridAxis = Annotated[tuple[float, float, int], entries(3, "a varied input is [lo, hi, n]")]
Bound = Annotated[tuple[float, float], entries(2, "a bound is [lo, hi]")]


def _checked_paths(names: list[str], what: str) -> None:
    for name in names:
        try:
            parse_input_path(name)
        except ValueError as exc:
            raise ValueError(f"{what}: {exc}") from None


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
    def _ordered(cls, bounds: dict[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
        _checked_paths(list(bounds), "sample.bounds")
        for name, (lo, hi) in bounds.items():
            if lo > hi:
                raise ValueError(f"sample.bounds[{name!r}]: lo {lo:g} exceeds hi {hi:g}")
        return bounds


class StudySpec(FrozenSpec):
    """Inputs of ``design-study``."""

    process: str = Field(..., description="The process evaluated for every design.")
    fixed: dict[str, JsonValue] = Field(
        default_factory=dict,
        description="The process's other inputs, exactly as it takes them.",
    )
    vary: dict[str, GridAxis] | None = Field(
        None,
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
    best_count: int = Field(5, ge=1, le=100, description="Best designs listed per objective.")
    plots: bool = Field(True, description="Render the study's plots (PNG/SVG).")

    @field_validator("process")
    @classmethod
    def _known(cls, process: str) -> str:
        from worker.processes import default_registry

        ids = [pid for pid in default_registry().ids() if pid not in NOT_STUDIED]
        if process not in ids:
            raise ValueError(
                f"{process!r} is not a process a study can run; one of {', '.join(ids)}"
            )
        return process

    @field_validator("vary")
    @classmethod
    def _grid(cls, vary: dict[str, tuple[float, float, int]] | None) -> Any:
        if vary is not None:
            _checked_paths(list(vary), "vary")
            for name, (lo, hi, n) in vary.items():
                if lo > hi or n < 1:
                    raise ValueError(f"vary[{name!r}]: needs lo <= hi and n >= 1, not "
                                     f"[{lo:g}, {hi:g}, {n}]")  # fmt: skip
        return vary

    @field_validator("objectives")
    @classmethod
    def _objective_paths(cls, objectives: dict[str, str]) -> dict[str, str]:
        for name in objectives:
            try:
                parse_result_path(name)
            except ValueError as exc:
                raise ValueError(f"objectives: {exc}") from None
        return objectives

    @model_validator(mode="after")
    def _one_design_set(self) -> StudySpec:
        if (self.vary is None) == (self.sample is None):
            raise ValueError("give exactly one of 'vary' (a grid) and 'sample'")
        space = self.designs
        if space.count > MAX_DESIGNS:
            raise ValueError(f"the grid holds {space.count:,} designs, more than {MAX_DESIGNS:,}")
        overlap = set(space.names) & set(self.fixed)
        if overlap:
            raise ValueError(f"{sorted(overlap)} are both fixed and varied")
        return self

    @property
    def designs(self) -> GridSpace | SampleSpace:
        if self.vary is not None:
            axes = tuple((name, lo, hi, n) for name, (lo, hi, n) in self.vary.items())
            return GridSpace(axes)
        assert self.sample is not None
        bounds = tuple((name, lo, hi) for name, (lo, hi) in self.sample.bounds.items())
        return SampleSpace(self.sample.method, bounds, self.sample.count, self.sample.seed)
