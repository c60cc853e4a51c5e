"""Exact joint-limited d_z along a ray from the base (docs/methods/planar-serial.md,
"Joint limits along a ray"): where its form changes (:mod:`.events`), bounds of it on an
interval (:mod:`.bounds`), and its range per interval and its d_z = 1 radii
(:mod:`.dexterity`, re-exported here)."""

from __future__ import annotations

from worker.families.planar_serial.kinematics.ray.dexterity import (
    RANGE_TOL,
    RayDexterity,
    RayRange,
    ray_dexterity,
)

__all__ = ["RANGE_TOL", "RayDexterity", "RayRange", "ray_dexterity"]
