"""Task points of the planar3r jobs: their result entries and shortfall notes."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_serial.jobs.dexterity_evaluation import FULL_DEXTERITY_TOL

__all__ = ["MAX_LISTED_SHORTFALLS", "shortfall_notes", "task_point_entries"]

#: Task points named one by one in the notes before the rest are summarised.
MAX_LISTED_SHORTFALLS = 20


def task_point_entries(
    labels: Sequence[str],
    points: NDArray[np.float64],
    d_z: NDArray[np.float64],
    regions: NDArray[np.int8],
) -> list[dict[str, Any]]:
    """One entry per task point, in order: label, x, y, distance, d_z, D, region."""
    return [
        {
            "label": label,
            "x": float(x),
            "y": float(y),
            "distance": float(np.hypot(x, y)),
            "d_z": float(dz),
            "D": float(dz) / 3.0,
            "region": int(region),
        }
        for label, (x, y), dz, region in zip(labels, points, d_z, regions, strict=True)
    ]


def shortfall_notes(entries: Sequence[dict[str, Any]], prefix: str = "") -> list[str]:
    """Notes naming each task point with d_z < 1 (the first 20, then a count)."""
    short = [e for e in entries if e["d_z"] < 1.0 - FULL_DEXTERITY_TOL]
    notes = [
        f"{prefix}task point {e['label']} ({e['x']:g}, {e['y']:g}) has d_z = {e['d_z']:.4f} "
        "< 1: not fully dexterous"
        for e in short[:MAX_LISTED_SHORTFALLS]
    ]
    if len(short) > MAX_LISTED_SHORTFALLS:
        notes.append(
            f"{prefix}{len(short) - MAX_LISTED_SHORTFALLS} more task points have d_z < 1 "
            "(see task_points)"
        )
    return notes
