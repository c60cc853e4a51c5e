"""The ``spm-conditioning-map`` preview: the job's indices over the samples and its
1/kappa maps over tilt x azimuth, nothing else (no closed-workspace minimum, no
sweeps, no files); the live explorer's evaluation (:mod:`worker.previews`)."""

from __future__ import annotations

from typing import Any

from worker.common.preview_arrays import map_entry
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.design_entries import indices_entry
from worker.families.spherical_parallel.jobs.pose_grids import inverse_condition_maps
from worker.families.spherical_parallel.jobs.workspace_sampling import (
    design_of,
    workspace_samples,
)
from worker.families.spherical_parallel.specs import ConditioningMapSpec

__all__ = ["conditioning_preview"]

_INDICES = (
    ("rms_inverse_condition", "C_n = sqrt(mean 1/κ²) (eq 25)"),
    ("mean_square_inverse_condition", "mean(1/κ²) (eq 28, the paper's 'C_n')"),
    ("gci", "GCI = mean(1/κ) (eq 24)"),
    ("min_inverse_condition", "min 1/κ over the samples"),
    ("max_inverse_condition", "max 1/κ over the samples"),
    ("min_abs_det_a", "min |det A| (eq 30)"),
)


def conditioning_preview(spec: ConditioningMapSpec) -> dict[str, Any]:
    """Indices over the workspace samples and one 1/kappa map (tilt x azimuth, deg) per
    map torsion, as plain JSON values."""
    design = design_of(spec.alpha1_deg, spec.alpha2_deg, spec.beta_deg, spec.gamma_deg)
    samples, _ = workspace_samples(spec.workspace)
    entry = indices_entry(sp.workspace_indices(design, samples, spec.branch))
    maps = inverse_condition_maps(design, spec.branch, spec.map_torsions,
                                  spec.workspace.tilt_max_deg,
                                  (spec.map_grid.azimuth, spec.map_grid.tilt))  # fmt: skip
    indices = [
        {"name": name, "label": label, "value": entry[name], "unit": ""} for name, label in _INDICES
    ]
    indices.append({"name": "real_samples", "label": f"samples reached (of {entry['samples']})",
                    "value": entry["real_samples"], "unit": ""})  # fmt: skip
    notes = []
    if not entry["all_real"]:
        notes.append(
            f"{entry['samples'] - entry['real_samples']} of {entry['samples']} samples have "
            "no real inverse kinematics: the indices are null (an infeasible design)."
        )
    return {
        "maps": [
            map_entry(
                f"1/κ at torsion ψ3 = {torsion:g}°",
                (maps.azimuth_deg, "azimuth ψ1", "deg"),
                (maps.tilt_deg, "tilt ψ2", "deg"),
                (values, "1/κ", ""),
            )
            for torsion, values in zip(maps.torsions_deg, maps.values, strict=True)
        ],
        "indices": indices,
        "notes": notes,
    }
