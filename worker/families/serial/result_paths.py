"""The numeric result paths of the serial-arm processes: units, symbols, meanings
(:mod:`worker.result_paths`; lengths in the job's ``length_unit``)."""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R

__all__ = [
    "SERIAL_INDICES_RESULT_PATHS",
    "SERIAL_REACH_RESULT_PATHS",
    "SERIAL_WORKSPACE_MAP_RESULT_PATHS",
]

SERIAL_INDICES_RESULT_PATHS = (
    R("arm.joints", "-", "$n$", "Movable joints."),
    R("characteristic_length", "length", "$L$", "The length dividing the linear rows for "
      "the inverse condition number (null: unscaled)."),
    R("poses[].configuration[]", "mixed", r"$q_i$", "Joint values as given: degrees "
      "(revolute), length_unit (prismatic)."),
    R("poses[].position[]", "length", r"$p$", "The tool point in the base frame."),
    R("poses[].rotation[][]", "-", "$R$", "The tool frame's rotation matrix (rows)."),
    R("poses[].phi_deg", "deg", r"$\phi$", "A planar arm's tool angle about z."),
    R("poses[].jacobian[][]", "mixed", "$J$", "The task Jacobian about the tool point: "
      "linear rows per radian (length_unit) or per length unit (pure), angular rows per "
      "radian (pure) or 0."),
    R("poses[].singular_values[]", "mixed", r"$\sigma_i$", "Singular values of the task "
      "Jacobian (of the scaled one with a characteristic length), largest first."),
    R("poses[].manipulability", "mixed", "$w$", "Yoshikawa's manipulability: the product of "
      "the task Jacobian's singular values."),
    R("poses[].inverse_condition", "-", r"$1/\kappa$", "sigma_min / sigma_max of the task "
      "Jacobian (scaled with a characteristic length)."),
    R("poses[].limit_distance[]", "mixed", r"$\Delta q_i$", "Per joint, the distance to "
      "the nearer limit: degrees (revolute), length_unit (prismatic); negative outside."),
    R("summary.configurations", "-", "", "Configurations evaluated."),
    R("summary.manipulability_min", "mixed", r"$w_{\min}$", "The least manipulability."),
    R("summary.manipulability_max", "mixed", r"$w_{\max}$", "The largest manipulability."),
    R("summary.inverse_condition_min", "-", r"$1/\kappa_{\min}$", "The least inverse "
      "condition number."),
    R("summary.inverse_condition_mean", "-", r"$1/\kappa$", "The mean inverse "
      "condition number."),
    R("summary.outside_limits", "-", "", "Configurations outside the joint limits."),
)  # fmt: skip

SERIAL_REACH_RESULT_PATHS = (
    R("arm.joints", "-", "$n$", "Movable joints."),
    R("characteristic_length", "length", "$L$", "The length dividing the linear rows for "
      "the inverse condition number (null: unscaled)."),
    R("seeds", "-", "", "Starting configurations per target of the numerical "
      "solver (with the closed form: for the targets it does not reach)."),
    R("seed", "-", "", "Seed of the starting configurations."),
    R("max_iterations", "-", "", "Damped least-squares iterations per target."),
    R("targets[].position[]", "length", "$p_t$", "The target point in the base frame."),
    R("targets[].rpy_deg[]", "deg", "", "The target orientation: roll, pitch, yaw."),
    R("targets[].configuration[]", "mixed", r"$q_i$", "The solution's joint values: "
      "degrees (revolute), length_unit (prismatic); the closest found if not reached."),
    R("targets[].residual.position", "length", r"$|p_t - p|$", "Distance of the tool "
      "point from the target."),
    R("targets[].residual.orientation_deg", "deg", r"$\Delta\theta$", "Angle between the "
      "tool's and the target's rotations (null: position only)."),
    R("targets[].tolerance.position", "length", "", "Position tolerance used."),
    R("targets[].tolerance.orientation_deg", "deg", "", "Orientation tolerance used."),
    R("targets[].solutions", "-", "", "Seeds (or closed-form branches) that reached the "
      "target."),
    R("targets[].manipulability", "mixed", "$w$", "Yoshikawa's manipulability at the "
      "solution (null: not reached)."),
    R("targets[].inverse_condition", "-", r"$1/\kappa$", "sigma_min / sigma_max of the task "
      "Jacobian at the solution (null: not reached)."),
    R("summary.targets", "-", "", "Targets."),
    R("summary.reached", "-", "", "Targets reached."),
    R("summary.reached_share", "-", "", "The share of targets reached, in [0, 1]."),
    R("summary.manipulability_min", "mixed", r"$w_{\min}$", "The least manipulability of "
      "the reached targets' solutions."),
    R("summary.manipulability_mean", "mixed", "$w$", "The mean manipulability of "
      "the reached targets' solutions."),
    R("summary.inverse_condition_min", "-", r"$1/\kappa_{\min}$", "The least inverse "
      "condition number of the reached targets' solutions."),
    R("summary.inverse_condition_mean", "-", r"$1/\kappa$", "The mean inverse condition "
      "number of the reached targets' solutions."),
)  # fmt: skip

SERIAL_WORKSPACE_MAP_RESULT_PATHS = (
    R("arm.joints", "-", "$n$", "Movable joints."),
    R("characteristic_length", "length", "$L$", "The length dividing the linear rows for "
      "the inverse condition number (null: unscaled).",
      optional="when the request gives a characteristic_length"),
    R("seed", "-", "", "Seed of the joint sampler."),
    R("voxel_size", "length", "$h$", "Edge of a voxel (pixel for a planar arm)."),
    R("orientation_bins.count", "-", "$K$", "Orientation bins."),
    R("orientation_bins.bands", "-", "", "Latitude bands of the sphere bins (1: phi bins)."),
    R("orientation_bins.cells_per_band", "-", "", "Longitude cells per band (phi bins)."),
    R("grid.shape[]", "-", "", "Nodes per axis."),
    R("grid.first[]", "length", "", "The first node per axis."),
    R("grid.last[]", "length", "", "The last node per axis."),
    R("summary.samples", "-", "$N$", "Joint samples drawn."),
    R("summary.samples_in_grid", "-", "", "Samples whose tool point fell in the grid."),
    R("summary.voxels", "-", "", "Voxels (pixels) of the grid."),
    R("summary.reached_voxels", "-", "", "Voxels with at least one sample."),
    R("summary.reached_volume", "length^3", "$V$", "Reached voxels x voxel volume "
      "(a spatial arm).", optional="a spatial arm's map (a planar arm's: reached_area)"),
    R("summary.reached_area", "length^2", "$A$", "Reached pixels x pixel area (a planar "
      "arm).", optional="a planar arm's map (a spatial arm's: reached_volume)"),
    R("summary.mean_reachability_index", "-", r"$r$", "Mean over the reached voxels "
      "of the fraction of orientation bins reached."),
    R("summary.full_orientation_voxels", "-", "", "Voxels reaching every orientation bin."),
    R("summary.manipulability_min", "mixed", r"$w_{\min}$", "The least manipulability "
      "sampled in the grid."),
    R("summary.manipulability_max", "mixed", r"$w_{\max}$", "The largest manipulability "
      "sampled in the grid."),
    R("summary.inverse_condition_mean", "-", r"$1/\kappa$", "Mean over the reached voxels "
      "of the per-voxel mean inverse condition number."),
    R("summary.inverse_condition_max", "-", r"$1/\kappa_{\max}$", "The largest inverse "
      "condition number sampled in the grid."),
    R("convergence.samples[]", "-", "", "The prefixes N/8, N/4, N/2, N of the samples."),
    R("convergence.reached_volume[]", "length^3", "$V$", "Reached volume at each prefix.",
      optional="a spatial arm's map"),
    R("convergence.reached_area[]", "length^2", "$A$", "Reached area at each prefix (a "
      "planar arm).", optional="a planar arm's map"),
    R("convergence.mean_reachability_index[]", "-", r"$r$", "Mean reachability index "
      "at each prefix."),
    R("convergence.relative_change_volume[]", "-", "", "|V_k - V_{k-1}| / V_k over each "
      "doubling."),
    R("convergence.relative_change_index[]", "-", "", "The same for the mean index."),
    R("convergence.tolerance", "-", "", "The largest relative change for convergence."),
)  # fmt: skip
