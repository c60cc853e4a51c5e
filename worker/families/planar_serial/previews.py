"""The live explorer's preview of ``planar3r-dexterity-map`` (:mod:`worker.previews`):
sliders for the three links, starting from the paper's Example 1 Case 3 (the design
(15, 14, 8) under its joint limits) on a 101 x 101 grid.  The computation loads when a
preview runs."""

from __future__ import annotations

from typing import Any

from worker.families.planar_serial.costs import SYNC_COST_LIMIT
from worker.families.planar_serial.specs import DexterityMapSpec
from worker.previews import DataChart, PreviewField, ProcessPreview

__all__ = ["DEXTERITY_MAP_CHART", "DEXTERITY_MAP_PREVIEW", "PREVIEW_COST_LIMIT"]

#: A preview may cost what a synchronous answer may: a 101 x 101 map under joint limits.
PREVIEW_COST_LIMIT = SYNC_COST_LIMIT


def _dexterity_preview(spec: DexterityMapSpec) -> dict[str, Any]:
    # lazy: numpy and the job modules load when a preview runs, not with the registry
    from worker.families.planar_serial.jobs.preview import dexterity_preview

    return dexterity_preview(spec)


DEXTERITY_MAP_PREVIEW = ProcessPreview(
    compute=_dexterity_preview,
    cost_limit=PREVIEW_COST_LIMIT,
    fields=(
        PreviewField("links.0", "l1 (first link)", "length", 0.5, 40.0, 0.5),
        PreviewField("links.1", "l2 (second link)", "length", 0.5, 40.0, 0.5),
        PreviewField("links.2", "l3 (third link)", "length", 0.5, 40.0, 0.5),
    ),
    start_example=1,
    start_overrides={"grid": {"points_per_axis": 101}, "plots": False},
)

#: A job's interactive heat map, from its dexterity_map.csv (d_z = 0: unreachable).
DEXTERITY_MAP_CHART = DataChart(
    "dexterity_map.csv", "x", "y", "d_z", "Dexterity d_z over the workspace", 0.0
)
