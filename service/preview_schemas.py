"""The preview document (``POST /v1/processes/{processID}/preview``): what the live
explorer draws, published in OpenAPI as the route's response model."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

__all__ = ["PreviewDocument", "PreviewIndex", "PreviewMap"]


class _Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class PreviewMap(_Frozen):
    """One heat map: ``z`` holds ``len(y)`` rows of ``len(x)`` values."""

    title: str
    x: list[float] = Field(..., description="The grid's x axis (columns), in `x_unit`.")
    x_label: str
    x_unit: str
    y: list[float] = Field(..., description="The grid's y axis (rows), in `y_unit`.")
    y_label: str
    y_unit: str
    z: list[list[float | None]] = Field(
        ..., description="The values, one row per y; null where there is none (unreachable)."
    )
    z_label: str
    z_unit: str = Field(..., description="The values' unit; '' for a ratio such as 1/kappa.")


class PreviewIndex(_Frozen):
    """One number of the summary (an index over the workspace, a count)."""

    name: str = Field(..., description="Its key, as in the job's result where it has one.")
    label: str
    value: float | None = Field(..., description="null: undefined for this design.")
    unit: str


class PreviewDocument(_Frozen):
    """A design's maps and indices, computed in the request; nothing was stored."""

    process_id: str
    maps: list[PreviewMap]
    indices: list[PreviewIndex]
    notes: list[str] = Field(default_factory=list)
    cost: int = Field(..., description="What these inputs cost, in `cost_unit`.")
    cost_limit: int = Field(..., description="The most a preview of this process may cost.")
    cost_unit: str
