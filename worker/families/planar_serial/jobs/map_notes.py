"""The notes and warnings of the ``planar3r-dexterity-map`` job.

Warnings say that the result holds less than it seems to: a map on which no grid node
is reachable (every number of ``summary`` and ``areas`` is then 0), or a task point the
arm cannot reach at all.  They lead the notes and are repeated in
``summary.warnings``, which the job page shows as a warning.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.jobs.dexterity_evaluation import LimitedJoints, WorkspaceGrid
from worker.families.planar_serial.jobs.regions import Bands, LimitedRay, region_2_note
from worker.families.planar_serial.jobs.task_points import MAX_LISTED_SHORTFALLS, shortfall_notes
from worker.families.planar_serial.specs import DexterityMapSpec

__all__ = ["map_notes", "map_warnings", "unreachable_labels"]


def unreachable_labels(task_entries: Sequence[dict[str, Any]]) -> list[str]:
    """Labels of the task points with d_z = 0, in order."""
    return [str(e["label"]) for e in task_entries if e["d_z"] <= 0.0]


def _named(entry: dict[str, Any]) -> str:
    return f"{entry['label']} ({entry['x']:g}, {entry['y']:g})"


def map_warnings(
    spec: DexterityMapSpec,
    grid: WorkspaceGrid,
    reachable_points: int,
    task_entries: Sequence[dict[str, Any]],
) -> list[str]:
    """An empty map, and task points out of reach, in words (empty list: neither)."""
    warnings = []
    if reachable_points == 0:
        nodes = grid.points_per_axis**2
        x_min, x_max, y_min, y_max = grid.bounds
        if spec.joint_limits_deg is None:
            inner, outer = planar_serial.reach_radii(spec.links)
            why = (
                f"the reachable annulus {inner:.6g} <= d <= {outer:.6g} falls between the "
                "nodes: use more points_per_axis or bounds nearer the base"
            )
        else:
            limits = [list(pair) for pair in spec.joint_limits_deg]
            why = (
                f"under the joint limits {limits} (degrees) the arm reaches none of them: "
                "check the limits, or use more points_per_axis or other bounds"
            )
        warnings.append(
            f"The map is empty: no node of the grid [{x_min:.6g}, {x_max:.6g}] x "
            f"[{y_min:.6g}, {y_max:.6g}] is reachable (d_z = 0 at all {nodes} nodes, so the "
            f"map's counts, means and grid areas are all 0); {why}."
        )
    out = [e for e in task_entries if e["d_z"] <= 0.0]
    if out:
        listed = ", ".join(_named(e) for e in out[:MAX_LISTED_SHORTFALLS])
        if len(out) > MAX_LISTED_SHORTFALLS:
            listed += f" and {len(out) - MAX_LISTED_SHORTFALLS} more"
        which = f"Task point {listed} is" if len(out) == 1 else f"Task points {listed} are"
        warnings.append(
            f"{which} out of reach (d_z = 0): the arm cannot reach "
            f"{'it' if len(out) == 1 else 'them'} in any orientation."
        )
    return warnings


def map_notes(
    spec: DexterityMapSpec,
    sampling: LimitedJoints | None,
    ray: LimitedRay | None,
    task_entries: list[dict[str, Any]],
    trajectory: dict[str, float | int] | None,
    regions: list[dict[str, Any]],
    bands: Bands,
) -> list[str]:
    """The notes after the warnings: Region 2, how d_z was computed, the shortfalls
    (``bands``: the unlimited arm's full-dexterity bands)."""
    notes = [region_2_note(spec.links, regions, ray, bands=bands)]
    if spec.joint_limits_deg is not None and sampling is None:
        notes.append("Every joint limit spans the full turn [-180, 180]: the exact closed form "
                     "for unlimited joints was used.")  # fmt: skip
    if sampling is not None and ray is not None:
        notes.append(_limited_note(spec, sampling, ray))
    notes.extend(shortfall_notes(task_entries))
    if trajectory is not None and trajectory["fully_dexterous_fraction"] < 1.0:
        percent = 100.0 * trajectory["fully_dexterous_fraction"]
        notes.append(
            f"The trajectory is fully dexterous at {percent:.1f}% of its "
            f"{trajectory['samples']} samples (min d_z = {trajectory['d_z_min']:.4f})."
        )
    return notes


def _limited_note(spec: DexterityMapSpec, sampling: LimitedJoints, ray: LimitedRay) -> str:
    if sampling.sampled:
        how = (
            f"sampled every {sampling.effective_step_deg:.6g}° ({sampling.samples} "
            "orientations, both elbow branches; features narrower than a step can be missed)"
        )
    else:
        how = (
            "exact: the feasible orientation arcs between closed-form events (up to "
            f"{sampling.events_per_point} per point, both elbow branches) are summed"
        )
        if "orientation_step_deg" in spec.model_fields_set:
            how += "; orientation_step_deg is not used by this method"
    return (
        f"Under joint limits d_z is {how}. The map is no longer radially symmetric, so the "
        f"radial section holds only along the ray at {ray.angle_deg:g}° (task points are "
        "not marked on it), and so do 'regions' and 'full_dexterity_bands': the "
        "joint-limited arm's along that ray, from the exact events whatever the method. "
        "The areas are the joint-limited arm's, counted on this map; the unlimited arm's "
        "areas, bands and regions are under areas.unlimited_reference."
    )
