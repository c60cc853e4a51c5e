"""The live explorer's preview of ``spm-conditioning-map`` (:mod:`worker.previews`):
sliders for the four design angles, starting from the paper's Table 1 design (the first
worked example) at its sampling (the 144 samples of the indices); its 1/kappa maps
every 5° of azimuth and 2.5° of tilt (73 x 25, a third of the job's default cells: the
redraw stays within the explorer's 150 ms).  The computation loads when a preview runs."""

from __future__ import annotations

from typing import Any

from worker.families.spherical_parallel.costs import CONDITIONING_MAP_SYNC_COST_LIMIT
from worker.families.spherical_parallel.specs import ConditioningMapSpec
from worker.previews import PreviewField, ProcessPreview

__all__ = ["CONDITIONING_MAP_PREVIEW"]


def _conditioning_preview(spec: ConditioningMapSpec) -> dict[str, Any]:
    # lazy: numpy and the job modules load when a preview runs, not with the registry
    from worker.families.spherical_parallel.jobs.preview import (
        conditioning_preview,
    )

    return conditioning_preview(spec)


CONDITIONING_MAP_PREVIEW = ProcessPreview(
    compute=_conditioning_preview,
    cost_limit=CONDITIONING_MAP_SYNC_COST_LIMIT,
    fields=(
        PreviewField("alpha1_deg", "α1 (base-side link angle)", "deg", 1.0, 179.0, 0.5),
        PreviewField("alpha2_deg", "α2 (platform-side link angle)", "deg", 1.0, 179.0, 0.5),
        PreviewField("beta_deg", "β (mobile pyramid half-angle)", "deg", 1.0, 179.0, 0.5),
        PreviewField("gamma_deg", "γ (base pyramid half-angle)", "deg", 0.0, 179.0, 0.5),
    ),
    start_overrides={"plots": False, "map_grid": {"azimuth": 73, "tilt": 25}},
)
