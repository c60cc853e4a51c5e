"""The numeric result paths of the planar3r processes: units, symbols, meanings
(:mod:`worker.result_paths`; lengths in the job's ``length_unit``)."""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R
from worker.result_paths import prefixed

__all__ = [
    "DESIGN_RESULT_PATHS",
    "DEXTERITY_MAP_RESULT_PATHS",
    "MAP_PATHS",
    "SYNTHESIS_RESULT_PATHS",
]

_MAP_SUMMARY = ("d_z_max", "d_z_mean_reachable", "D_mean_reachable", "reachable_points",
                "fully_dexterous_points")  # fmt: skip
_MAP_AREAS = ("reachable", "fully_dexterous", "reachable_grid", "fully_dexterous_grid",
              "cell_area", "unlimited_reference.reachable",
              "unlimited_reference.fully_dexterous")  # fmt: skip
#: The dexterity map's paths read from the map over the grid (each design's own map, as
#: the job's): its study kernel's (:mod:`.study`).
MAP_PATHS = (
    *(f"summary.{name}" for name in _MAP_SUMMARY),
    *(f"areas.{name}" for name in _MAP_AREAS),
)

_SAMPLED = "with joint limits and method 'orientation-sampling'"

_LINKS = R("links[]", "length", "$l_i$", "The links l1, l2, l3, from the base.")
_LIMITS = R("joint_limits_deg[][]", "deg", r"$\theta_i$",
            "Joint limits [lower, upper] of each joint (null without limits).")  # fmt: skip
_BANDS = R("full_dexterity_bands[][]", "length", "$d$", "Exact distance bands [r0, r1] "
           "from the base where d_z = 1 (revolute joints).")  # fmt: skip
_MAP_BANDS = R("full_dexterity_bands[][]", "length", "$d$", "Exact distance bands [r0, r1] "
               "from the base where d_z = 1: with revolute joints at every angle, under "
               "joint limits the limited arm's along the radial section's ray.")  # fmt: skip

_GRID = (
    R("grid.bounds[]", "length", "", "Grid bounds [x_min, x_max, y_min, y_max]."),
    R("grid.points_per_axis", "-", "", "Grid nodes per axis."),
    R("grid.step[]", "length", "", "Grid spacing [dx, dy]."),
)
_ORIENTATIONS = (
    R("orientation_step_deg", "deg", "", "The orientation sampling step used.",
      optional=_SAMPLED),
    R("orientation_samples", "-", "", "Orientations sampled per point.", optional=_SAMPLED),
    R("elbow_branches", "-", "", "Elbow branches evaluated under joint limits (both)."),
    R("events_per_point", "-", "", "Most closed-form events per point (exact events)."),
)  # fmt: skip

_TASK_POINTS = (
    R("x", "length", "$x$", "The task point's x."),
    R("y", "length", "$y$", "The task point's y."),
    R("distance", "length", "$d$", "Its distance from the base."),
    R("d_z", "-", "$d_z$", "Orientation dexterity there: the reachable fraction of a full "
      "turn of the end-effector (eqs 2-3)."),
    R("D", "-", "$D$", "Dexterity index D = d_z / 3 (eq 5)."),
    R("region", "-", "", "The paper's region (1-4) it lies in."),
)  # fmt: skip
_TRAJECTORY = (
    R("samples", "-", "", "Trajectory samples evaluated."),
    R("d_z_mean", "-", r"$\mathrm{mean}\,d_z$", "Mean d_z along the trajectory (eq 4)."),
    R("D_mean", "-", r"$\mathrm{mean}\,D$", "Mean D along the trajectory (eq 4)."),
    R("d_z_min", "-", r"$\min\,d_z$", "Least d_z along the trajectory."),
    R("fully_dexterous_fraction", "-", "", "Share of the samples where d_z = 1."),
)

_REGIONS = (
    R("region", "-", "", "Region number 1-4 (the paper's §5)."),
    R("d_from", "length", "$d$", "Distance from the base where the region starts."),
    R("d_to", "length", "$d$", "Distance from the base where the region ends."),
    R("fully_dexterous_bands[][]", "length", "$d$",
      "Exact bands inside the region where d_z = 1 (under joint limits along the radial "
      "section's ray)."),
    R("d_z_min", "-", r"$\min\,d_z$", "Least d_z over the region along the radial "
      "section's ray (exact events under joint limits)."),
    R("d_z_min_at", "length", "$d$", "The distance where that least d_z is reached."),
    R("d_z_max", "-", r"$\max\,d_z$", "Largest d_z over the region along the ray."),
)  # fmt: skip

_UNLIMITED_REGIONS = (
    R("region", "-", "", "Region number 1-4 (the paper's §5)."),
    R("d_from", "length", "$d$", "Distance from the base where the region starts."),
    R("d_to", "length", "$d$", "Distance from the base where the region ends."),
    R("fully_dexterous_bands[][]", "length", "$d$",
      "Exact bands inside the region where d_z = 1 without joint limits."),
    R("d_z_min", "-", r"$\min\,d_z$", "Least d_z over the region without joint limits."),
    R("d_z_min_at", "length", "$d$", "The distance where that least d_z is reached."),
    R("d_z_max", "-", r"$\max\,d_z$", "Largest d_z over the region without joint limits."),
)  # fmt: skip

_AREAS = (
    R("reachable", "length^2", "", "Reachable area: exact (revolute joints) or counted on "
      "the map (the joint-limited arm)."),
    R("fully_dexterous", "length^2", "", "Fully dexterous area (d_z = 1), likewise."),
    R("reachable_grid", "length^2", "", "Reachable area counted on the grid."),
    R("fully_dexterous_grid", "length^2", "", "Fully dexterous area counted on the grid."),
    R("cell_area", "length^2", "", "Area of one grid cell."),
    R("unlimited_reference.reachable", "length^2", "",
      "Exact reachable area of the same links without joint limits."),
    R("unlimited_reference.fully_dexterous", "length^2", "",
      "Exact fully dexterous area without joint limits."),
    R("unlimited_reference.full_dexterity_bands[][]", "length", "$d$",
      "Exact bands with d_z = 1 without joint limits."),
    *prefixed("unlimited_reference.regions[]", _UNLIMITED_REGIONS),
)  # fmt: skip

_SUMMARY = (
    R("d_z_max", "-", r"$\max\,d_z$", "Largest d_z on the grid."),
    R("d_z_mean_reachable", "-", r"$\mathrm{mean}\,d_z$", "Mean d_z over the reachable nodes."),
    R("D_mean_reachable", "-", r"$\mathrm{mean}\,D$", "Mean D over the reachable nodes."),
    R("reachable_points", "-", "", "Reachable grid nodes (d_z > 0)."),
    R("fully_dexterous_points", "-", "", "Fully dexterous grid nodes (d_z = 1)."),
)

DEXTERITY_MAP_RESULT_PATHS = (
    _LINKS,
    _LIMITS,
    *prefixed("discretisation", _GRID),
    *prefixed("discretisation", _ORIENTATIONS),
    R("discretisation.radial_section.angle_deg", "deg", r"$\phi$",
      "Direction of the radial section's ray."),
    R("discretisation.radial_section.samples", "-", "", "Distances sampled along the ray."),
    R("discretisation.radial_section.d_to", "length", "$d$",
      "Farthest distance of the radial section."),
    *prefixed("regions[]", _REGIONS),
    _MAP_BANDS,
    *prefixed("areas", _AREAS),
    *prefixed("summary", _SUMMARY),
    *prefixed("task_points[]", _TASK_POINTS),
    *prefixed("trajectory", _TRAJECTORY),
)  # fmt: skip


def _grashof(at: str) -> tuple[R, ...]:
    return (
        R(f"grashof.{at}.lengths[]", "length", "",
          f"The virtual four-bar's lengths [l1, l2, l3, d] at {at}."),
        R(f"grashof.{at}.s_plus_l", "length", "$s + l$",
          "Shortest plus longest link (Grashof: s + l <= p + q)."),
        R(f"grashof.{at}.p_plus_q", "length", "$p + q$", "The other two links' sum."),
        R(f"grashof.{at}.d", "length", "$d$", f"The distance {at}."),
        R(f"paper_conditions.{at}.d", "length", "$d$", f"The distance {at}."),
    )  # fmt: skip


_CASES = (
    R("case", "-", "", "The paper's case: 1 ideal, 2 with l2 and l3 swapped, 3 under joint "
      "limits."),
    _LINKS,
    _LIMITS,
    R("full_dexterity_bands[][]", "length", "$d$", "Exact bands with d_z = 1 (null under "
      "joint limits)."),
    R("fully_dexterous_area", "length^2", "", "Fully dexterous area."),
    R("reachable_area", "length^2", "", "Reachable area."),
    R("fully_dexterous_fraction", "-", "", "Fully dexterous share of the reachable area."),
    R("fully_dexterous_area_grid", "length^2", "", "Fully dexterous area counted on the grid."),
    R("reachable_area_grid", "length^2", "", "Reachable area counted on the grid."),
    *prefixed("task_points[]", _TASK_POINTS),
    *prefixed("trajectory", _TRAJECTORY),
)  # fmt: skip

SYNTHESIS_RESULT_PATHS = (
    R("d_min", "length", r"$d_{\min}$", "Exact smallest distance of the task from the base."),
    R("d_max", "length", r"$d_{\max}$", "Exact largest distance of the task from the base."),
    R("d_min_at[]", "length", "", "Where d_min is attained, [x, y]."),
    R("d_max_at[]", "length", "", "Where d_max is attained, [x, y]."),
    R("d_min_used", "length", r"$d_{\min}$", "d_min fed to the design (rounded if asked)."),
    R("d_max_used", "length", r"$d_{\max}$", "d_max fed to eqs (10)-(11)."),
    R("l3", "length", "$l_3$", "The chosen last link."),
    _LINKS,
    *_grashof("d_min"),
    *_grashof("d_max"),
    _BANDS,
    R("full_dexterity_condition.band[]", "length", "$d$",
      "[l3 + |l1 - l2|, l1 + l2 - l3]: the distances where d_z = 1."),
    *prefixed("task_points[]", _TASK_POINTS),
    *prefixed("cases[]", _CASES),
    *prefixed("discretisation", _GRID),
    *prefixed("discretisation", _ORIENTATIONS),
    R("discretisation.trajectory_samples", "-", "", "Trajectory samples evaluated."),
)  # fmt: skip

_DESIGN = (
    _LINKS,
    R("base[]", "length", "", "The base position [x, y] in the task's frame."),
    R("min_dz", "-", r"$\min\,d_z$", "Least d_z over the task points and trajectory."),
    R("mean_dz", "-", r"$\mathrm{mean}\,d_z$", "Mean d_z over them."),
    R("total_length", "length", "$l_1 + l_2 + l_3$", "The arm's total length."),
    R("task_points[].x", "length", "$x$", "The task point's x."),
    R("task_points[].y", "length", "$y$", "The task point's y."),
    R("task_points[].d_z", "-", "$d_z$", "d_z at the task point."),
    *prefixed("trajectory", _TRAJECTORY),
)

DESIGN_RESULT_PATHS = (
    R("dz_target", "-", r"$d_{z,\mathrm{target}}$", "The d_z every point must keep "
      "('min_length')."),
    _LIMITS,
    *prefixed("optimum", _DESIGN),
    *prefixed("paper_rule", _DESIGN),
    R("paper_rule.d_min_used", "length", r"$d_{\min}$", "d_min fed to eqs (10)-(11)."),
    R("paper_rule.d_max_used", "length", r"$d_{\max}$", "d_max fed to eqs (10)-(11)."),
    R("improvement.min_dz", "-", r"$\Delta\min\,d_z$", "Gain in the least d_z over the "
      "paper's rule ('max_min_dz')."),
    R("improvement.relative", "-", "", "That gain relative to the rule's least d_z."),
    R("improvement.total_length", "length", "", "Length saved over the paper's rule "
      "('min_length')."),
    R("convergence.seed", "-", "", "The search's seed."),
    R("convergence.evaluations", "-", "", "Designs evaluated in all."),
    R("convergence.generations", "-", "", "Generations of the global search."),
    R("convergence.best_per_generation[].generation", "-", "", "The generation."),
    R("convergence.best_per_generation[].min_dz", "-", r"$\min\,d_z$",
      "The best design's least d_z."),
    R("convergence.best_per_generation[].total_length", "length", "$l_1 + l_2 + l_3$",
      "The best design's total length."),
    R("convergence.best_per_generation[].score", "-", "", "What the search minimises "
      "(docs/methods/planar-serial.md)."),
    R("convergence.kept_start", "-", "", "The start whose best design is reported."),
    R("convergence.agreeing_starts", "-", "", "Starts whose best score is within "
      "agreement_tol of the best (success needs two)."),
    R("convergence.agreement_tol", "-", "", "Scores closer than this agree (score units: "
      "d_z for 'max_min_dz', a share of total_length_max for 'min_length')."),
    R("convergence.starts[].start", "-", "", "The start's index."),
    R("convergence.starts[].seed", "-", "", "The start's own seed (spawned from seed)."),
    R("convergence.starts[].score", "-", "", "Its best score."),
    R("convergence.starts[].min_dz", "-", r"$\min\,d_z$", "Its best design's least d_z."),
    R("convergence.starts[].total_length", "length", "$l_1 + l_2 + l_3$",
      "Its best design's total length."),
    R("convergence.starts[].links[]", "length", "$l_i$", "Its best design's links."),
    R("convergence.starts[].base[]", "length", "", "Its best design's base [x, y]."),
    R("convergence.starts[].evaluations", "-", "", "Designs it evaluated."),
    R("convergence.global_search.generations", "-", "", "Generations run."),
    R("convergence.global_search.population", "-", "", "Designs per generation."),
    R("convergence.global_search.evaluations", "-", "", "Designs evaluated."),
    R("convergence.global_search.best_score", "-", "", "Its best score."),
    R("convergence.polish.evaluations", "-", "", "Designs evaluated by the polish."),
    R("convergence.polish.score_gain", "-", "", "Score gained by the polish."),
    R("search_space.link_bounds[][]", "length", "$l_i$", "[lower, upper] of each link."),
    R("search_space.total_length_max", "length", "", "Longest total length allowed."),
    R("search_space.base_box[]", "length", "", "Where the base may go, [x_min, x_max, "
      "y_min, y_max] (null: at the origin)."),
    R("search_space.l3_held", "length", "$l_3$", "The tool link's held length (null "
      "when link_bounds designs it)."),
    R("search_space.free_variables", "-", "", "Variables searched over."),
    R("evaluation_points.task_points", "-", "", "Task points in the objective."),
    R("evaluation_points.trajectory_samples", "-", "", "Trajectory samples in the objective."),
)  # fmt: skip
