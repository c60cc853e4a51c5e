"""The live explorer's preview of ``planar2dof-conditioning-map``
(:mod:`worker.previews`): sliders for the distal links l2 (delta = l2/l1) and the
limit 1/kappa0 of W_kappa0, starting from the paper's Figs 4-5(a) (the isotropic design
delta = 1.5, the first worked example) on a 101 x 101 grid.  The computation loads when
a preview runs."""

from __future__ import annotations

from typing import Any

from worker.families.planar_parallel.costs import CONDITIONING_MAP_SYNC_COST_LIMIT
from worker.families.planar_parallel.specs import ConditioningMapSpec
from worker.previews import DataChart, PreviewField, ProcessPreview

__all__ = ["CONDITIONING_MAP_CHART", "CONDITIONING_MAP_PREVIEW", "PREVIEW_COST_LIMIT"]

#: A preview may cost what a synchronous answer may (the process prices the exact
#: W_kappa0 boundary, which a preview does not compute: a 201 x 201 grid fits, ~70 ms).
PREVIEW_COST_LIMIT = CONDITIONING_MAP_SYNC_COST_LIMIT


def _conditioning_preview(spec: ConditioningMapSpec) -> dict[str, Any]:
    # lazy: numpy and the job modules load when a preview runs, not with the registry
    from worker.families.planar_parallel.jobs.preview import (
        conditioning_preview,
    )

    return conditioning_preview(spec)


CONDITIONING_MAP_PREVIEW = ProcessPreview(
    compute=_conditioning_preview,
    cost_limit=PREVIEW_COST_LIMIT,
    fields=(
        PreviewField("l2", "l2 (distal links; δ = l2/l1)", "length", 1.0, 4.0, 0.01),
        PreviewField("inverse_condition_limit", "1/κ0 (limit of W_κ0)", "", 0.05, 0.95, 0.01),
    ),
    start_overrides={"grid": {"points_per_axis": 101}, "plots": False},
)

#: A job's interactive heat map, from its conditioning_map.csv (NaN: unreachable).
CONDITIONING_MAP_CHART = DataChart(
    "conditioning_map.csv", "x", "y", "inverse_condition", "1/κ over the workspace"
)
