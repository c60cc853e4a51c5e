"""Validated inputs of ``fourbar-grashof``: a four-bar chain and its fixed link."""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import BeforeValidator, Field, ValidationError, ValidationInfo, model_validator

from worker.common.numeric_ranges import length_ratio_problem, ratio_schema
from worker.common.specs import FrozenSpec
from worker.families.chains.kinematics.fourbar import CHANGE_POINT_RTOL
from worker.families.chains.specs import Length, chain_error, plots_field, unit_field
from worker.study_kernels import in_study_template

__all__ = ["FourBarGrashofSpec"]


def _four_lengths(value: Any) -> Any:
    if isinstance(value, list | tuple) and len(value) != 4:
        raise ValueError(
            f"lengths needs four link lengths in order round the loop, not {len(value)}"
        )
    return value


class FourBarGrashofSpec(FrozenSpec):
    """Inputs of ``fourbar-grashof``: a four-bar chain and its fixed link."""

    lengths: Annotated[tuple[Length, Length, Length, Length], BeforeValidator(_four_lengths)] = (
        Field(
            ...,
            json_schema_extra={**ratio_schema(), "x-unit": "length"},
            description="The four link lengths in order round the loop; link i is joined to "
            "links i-1 and i+1 (mod 4). Each must be shorter than the sum of the other three, "
            "or the loop cannot be assembled (or only lies flat and cannot move). Each in "
            "[1e-6, 1e6], the longest at most 1e6 times the shortest.",
        )
    )
    ground: int = Field(
        ...,
        ge=0,
        le=3,
        strict=True,
        description="Index (0-3) of the fixed link. The input is link ground+1, the coupler "
        "ground+2 and the output ground+3 (mod 4).",
    )
    length_unit: str = unit_field()
    plots: bool = plots_field()

    @model_validator(mode="after")
    def _loop_closes(self, info: ValidationInfo) -> FourBarGrashofSpec:
        """Like a chain's loop, a four-bar closes only if its longest link is shorter than
        the sum of the other three (within :data:`CHANGE_POINT_RTOL` of the total).  A
        design study's template leaves both checks to its kernel (per design)."""
        if in_study_template(info.context):
            return self
        spread = length_ratio_problem(self.lengths, "lengths")
        if spread is not None:
            raise ValidationError.from_exception_data(
                type(self).__name__, [chain_error(("lengths",), spread, self.lengths)]
            )
        longest = max(range(4), key=self.lengths.__getitem__)
        rest = math.fsum(v for k, v in enumerate(self.lengths) if k != longest)
        if self.lengths[longest] >= rest - CHANGE_POINT_RTOL * math.fsum(self.lengths):
            message = (
                f"lengths[{longest}]: the loop cannot close: link {longest} "
                f"({self.lengths[longest]:g}) is not shorter than the sum of the other three "
                f"({rest:g})"
            )
            raise ValidationError.from_exception_data(
                type(self).__name__, [chain_error(("lengths", longest), message, self.lengths)]
            )
        return self
