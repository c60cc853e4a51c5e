"""Serial arms of the user's own (docs/methods/serial.md): DH tables or URDF chains.

``serial-indices``: pose, Jacobian and dexterity indices of given joint configurations.
``serial-reach``: which target poses the arm reaches within its limits (inverse kinematics).
``serial-workspace-map``: reachable workspace and dexterity on a voxel grid, with convergence.

Importing this package builds the process definitions and nothing else: the job modules
(matplotlib figures) and the URDF parser are imported when needed.
"""

from __future__ import annotations

from worker.contract import JobContext, JobOutcome
from worker.families.serial.costs import (
    INDICES_COST_LIMIT,
    INDICES_SYNC_COST_LIMIT,
    MAP_COST_LIMIT,
    MAP_SYNC_COST_LIMIT,
    REACH_COST_LIMIT,
    REACH_SYNC_COST_LIMIT,
    TIME_LIMIT_S,
    indices_cost,
    map_cost,
    reach_cost,
)
from worker.families.serial.examples import (
    SERIAL_INDICES_EXAMPLES,
    SERIAL_REACH_EXAMPLES,
    SERIAL_WORKSPACE_MAP_EXAMPLES,
)
from worker.families.serial.reach_spec import MAX_TARGETS, SerialReachSpec
from worker.families.serial.result_paths import (
    SERIAL_INDICES_RESULT_PATHS,
    SERIAL_REACH_RESULT_PATHS,
    SERIAL_WORKSPACE_MAP_RESULT_PATHS,
)
from worker.families.serial.specs import MAX_CONFIGURATIONS, SerialIndicesSpec
from worker.families.serial.workspace_spec import MAX_SAMPLES, SerialWorkspaceMapSpec
from worker.processes import FamilyInfo, ProcessDefinition, data_files, figure_files

__all__ = ["FAMILY", "PROCESSES", "SERIAL_INDICES", "SERIAL_REACH", "SERIAL_WORKSPACE_MAP"]


def _run_serial_indices(spec: SerialIndicesSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib) loads when a job runs, not with the registry
    from worker.families.serial.jobs.indices import run_serial_indices

    return run_serial_indices(spec, ctx)


SERIAL_INDICES = ProcessDefinition(
    id="serial-indices",
    title="Serial arm (DH or URDF): pose, Jacobian and dexterity indices",
    method_doc="serial",
    result_paths=SERIAL_INDICES_RESULT_PATHS,
    files=figure_files("arm", "The arm and its manipulability ellipsoids"),
    description=(
        "Your own serial arm, as a DH table (standard or modified) or a URDF chain from "
        "base_link to tip_link (docs/methods/serial.md), at given joint configurations "
        "(degrees for revolute joints, length_unit for prismatic ones): per configuration "
        "the tool's position and rotation in the base frame, the geometric Jacobian about "
        "the tool point (rows [linear; angular], or [x, y, phi] for a planar arm), its "
        "singular values, Yoshikawa's manipulability, the inverse condition number "
        "(optionally with the linear rows divided by a characteristic length) and each "
        "joint's distance to its limits; a figure of the arm with its manipulability "
        f"ellipsoids. Cost: configurations x joints, at most {INDICES_COST_LIMIT:,} "
        f"({MAX_CONFIGURATIONS:,} configurations); up to {INDICES_SYNC_COST_LIMIT:,} "
        "answered synchronously with 'Prefer: wait=N'."
    ),
    inputs_model=SerialIndicesSpec,
    run=_run_serial_indices,
    examples=SERIAL_INDICES_EXAMPLES,
    outputs={
        "arm": "The arm: source (dh or urdf), convention, joints, joint_names, joint_types, "
        "planar, task_space.",
        "length_unit": "The length unit.",
        "characteristic_length": "The length dividing the linear rows (null: unscaled).",
        "poses": "Per configuration: configuration, position, rotation, phi_deg (planar), "
        "jacobian, singular_values, manipulability, inverse_condition, limit_distance, "
        "within_limits.",
        "summary": "configurations, manipulability_min/max, inverse_condition_min/mean, "
        "outside_limits.",
    },
    cost=indices_cost,
    cost_limit=INDICES_COST_LIMIT,
    cost_unit="configurations x joints",
    sync_cost_limit=INDICES_SYNC_COST_LIMIT,
    seconds_per_cost=2e-6,
    seconds_per_run=0.02,
    time_limit_s=TIME_LIMIT_S,
)


def _run_serial_reach(spec: SerialReachSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib) loads when a job runs, not with the registry
    from worker.families.serial.jobs.reach import run_serial_reach

    return run_serial_reach(spec, ctx)


SERIAL_REACH = ProcessDefinition(
    id="serial-reach",
    title="Serial arm (DH or URDF): which target poses it reaches",
    method_doc="serial",
    result_paths=SERIAL_REACH_RESULT_PATHS,
    files=figure_files("reach", "Targets reached or not, and the arm at a few solutions"),
    description=(
        "Your own serial arm (a DH table or a URDF chain, docs/methods/serial.md) and "
        "target poses of its tool (a position, an optional roll-pitch-yaw orientation and "
        "tolerances each): per target whether the arm reaches it within its joint limits, "
        "the joint solution (closed form for a planar 3R arm; otherwise damped least "
        "squares from 'seeds' starting configurations drawn with 'seed', so the same "
        "request gives the same answer), its residual, manipulability and inverse "
        "condition number, and the share of targets reached; a figure of the targets and "
        f"the arm at a few solutions. Cost: targets x seeds x max_iterations x joints, at "
        f"most {REACH_COST_LIMIT:,} ({MAX_TARGETS:,} targets); up to "
        f"{REACH_SYNC_COST_LIMIT:,} answered synchronously with 'Prefer: wait=N'."
    ),
    inputs_model=SerialReachSpec,
    run=_run_serial_reach,
    examples=SERIAL_REACH_EXAMPLES,
    outputs={
        "arm": "The arm: source (dh or urdf), convention, joints, joint_names, joint_types, "
        "planar, task_space.",
        "length_unit": "The length unit.",
        "characteristic_length": "The length dividing the linear rows (null: unscaled).",
        "solver": "'closed-form planar 3R' or 'damped least squares'.",
        "seeds": "Starting configurations per target of the numerical solver.",
        "seed": "Seed of the starting configurations.",
        "max_iterations": "Damped least-squares iterations per target.",
        "targets": "Per target: position, rpy_deg, reached, configuration, residual "
        "(position, orientation_deg), tolerance, solutions, manipulability, "
        "inverse_condition.",
        "summary": "targets, reached, reached_share, manipulability_min/mean, "
        "inverse_condition_min/mean (over the reached targets).",
    },
    cost=reach_cost,
    cost_limit=REACH_COST_LIMIT,
    cost_unit="targets x seeds x iterations x joints",
    sync_cost_limit=REACH_SYNC_COST_LIMIT,
    seconds_per_cost=1.5e-6,
    seconds_per_run=0.05,
    time_limit_s=TIME_LIMIT_S,
)


def _run_serial_workspace_map(spec: SerialWorkspaceMapSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib) loads when a job runs, not with the registry
    from worker.families.serial.jobs.workspace_map import run_serial_workspace_map

    return run_serial_workspace_map(spec, ctx)


SERIAL_WORKSPACE_MAP = ProcessDefinition(
    id="serial-workspace-map",
    title="Serial arm (DH or URDF): reachable workspace and dexterity map",
    method_doc="serial",
    result_paths=SERIAL_WORKSPACE_MAP_RESULT_PATHS,
    files=(
        *data_files("workspace_map", "Workspace map: reached voxels and their indices"),
        *figure_files("workspace_slices", "Reachability index: slices through the grid"),
        *figure_files("workspace_3d", "Reached voxels in 3-D"),
        *figure_files("workspace_histograms", "Histograms of the indices over the reached voxels"),
    ),
    description=(
        "Your own serial arm (a DH table or a URDF chain, docs/methods/serial.md): joint "
        "samples within its limits ('sobol', 'uniform' or a 'grid', seeded) through "
        "vectorised forward kinematics give, on a node-centred voxel grid ('voxel_size'; "
        "pixels for a planar arm; 'bounds' or the arm's reach), which voxels the tool "
        "point reaches, the reachability index (the fraction of 'orientation_bins' "
        "reached: equal-area tool-axis cells on the sphere, or tool-angle bins for a "
        "planar arm) and per-voxel min/mean/max of the manipulability and the inverse "
        "condition number; a convergence report (reached volume and mean index at N/8, "
        "N/4, N/2 and N samples against 'convergence_tolerance'); the grid as NPZ, the "
        "reached voxels as CSV, slices, a 3-D view and histograms. Cost: samples x "
        f"joints, at most {MAP_COST_LIMIT:,} ({MAX_SAMPLES:,} samples); up to "
        f"{MAP_SYNC_COST_LIMIT:,} answered synchronously with 'Prefer: wait=N'."
    ),
    inputs_model=SerialWorkspaceMapSpec,
    run=_run_serial_workspace_map,
    examples=SERIAL_WORKSPACE_MAP_EXAMPLES,
    outputs={
        "arm": "The arm: source (dh or urdf), convention, joints, joint_names, joint_types, "
        "planar, task_space.",
        "length_unit": "The length unit.",
        "characteristic_length": "The length dividing the linear rows (null: unscaled).",
        "sampler": "The joint sampler.",
        "seed": "Seed of the sampler.",
        "voxel_size": "Voxel (pixel) edge.",
        "orientation_bins": "count, of (tool angle or tool axis), bands, cells_per_band.",
        "grid": "axes, shape, first and last node per axis, cell (pixel or voxel).",
        "summary": "samples, samples_in_grid, voxels, reached_voxels, reached_volume "
        "(reached_area for a planar arm), mean_reachability_index, full_orientation_voxels, "
        "manipulability_min/max, inverse_condition_mean/max.",
        "convergence": "samples (N/8, N/4, N/2, N), reached_volume (reached_area), "
        "mean_reachability_index, relative_change_volume, relative_change_index, "
        "tolerance, met.",
    },
    cost=map_cost,
    cost_limit=MAP_COST_LIMIT,
    cost_unit="samples x joints",
    sync_cost_limit=MAP_SYNC_COST_LIMIT,
    seconds_per_cost=8e-7,
    seconds_per_run=0.5,
    time_limit_s=TIME_LIMIT_S,
)

#: Who this family is: the tag its operations are listed under, and its sources.
FAMILY = FamilyInfo(
    name="serial",
    tag="Serial arms of your own (DH or URDF)",
    description=(
        "Any serial arm given as a DH table or a URDF: poses, Jacobians and dexterity "
        "indices, checked against the Robotics Toolbox for Python."
    ),
    paper="the arm's published DH table",
)

#: This family's processes, in the order GET /v1/processes lists them.
PROCESSES = (SERIAL_INDICES, SERIAL_REACH, SERIAL_WORKSPACE_MAP)
