"""The numeric result paths of the planar2dof processes: units, symbols, meanings
(:mod:`worker.result_paths`).  The conditioning map's lengths are in the job's
``length_unit``; the optimisation is normalised as the paper is (``l1`` = 1)."""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R
from worker.result_paths import prefixed

__all__ = [
    "CONDITIONING_MAP_RESULT_PATHS",
    "GRID_PATHS",
    "OPTIMISATION_RESULT_PATHS",
    "REGION_PATHS",
]

#: The conditioning map's paths its study kernel (:mod:`.study`) reads from the designs'
#: grids, and from W_kappa0's column search.
GRID_PATHS = (
    "summary.reachable_points", "summary.reachable_area_grid", "summary.inverse_condition.min",
    "summary.inverse_condition.max", "summary.inverse_condition.mean", "w_kappa0.area_grid",
)  # fmt: skip
REGION_PATHS = (
    "w_kappa0.area", "w_kappa0.rectangle_region_area", "w_kappa0.largest_inverse_condition.value",
    "w_kappa0.largest_inverse_condition.x", "w_kappa0.largest_inverse_condition.y",
)  # fmt: skip

_KAPPA = r"$1/\kappa$"
_BETA_MIN = r"$\beta_{\min}$"


def _stats(name: str, unit: str, symbol: str, what: str) -> tuple[R, ...]:
    return tuple(
        R(f"summary.{name}.{stat}", unit, rf"$\{stat}\,{symbol[1:-1]}$" if stat != "mean"
          else rf"$\mathrm{{mean}}\,{symbol[1:-1]}$", f"{word} {what} over the reachable nodes.")
        for stat, word in (("min", "Least"), ("max", "Largest"), ("mean", "Mean"))
    )  # fmt: skip


CONDITIONING_MAP_RESULT_PATHS = (
    R("l1", "length", "$l_1$", "Proximal link length as given."),
    R("l2", "length", "$l_2$", "Distal link length as given."),
    R("e", "length", "$e$", "Half-distance of the actuated joints: given, or by eq (12)."),
    R("delta", "-", r"$\delta$", "l2 / l1 (proximal-arm type)."),
    R("working_mode[]", "-", "", "The working mode [sgn1, sgn2]."),
    R("isotropic_point.x", "length", "$x$", "The isotropic (or best-conditioned) point's x."),
    R("isotropic_point.y", "length", "$y$", "Its y."),
    R("isotropic_point.inverse_condition", "-", _KAPPA, "1/kappa there (eq 7)."),
    R("isotropic_point.min_pressure_angle_deg", "deg", _BETA_MIN,
      "The smaller pressure angle there (eq 15)."),
    R("summary.reachable_points", "-", "", "Reachable grid nodes."),
    R("summary.reachable_area_grid", "length^2", "", "Reachable area counted on the grid."),
    *_stats("inverse_condition", "-", _KAPPA, "1/kappa (eq 7)"),
    *_stats("min_pressure_angle_deg", "deg", _BETA_MIN, "beta_min (eq 15)"),
    R("w_kappa0.inverse_condition_limit", "-", r"$1/\kappa_0$", "The limit 1/kappa0."),
    R("w_kappa0.area", "length^2", "", "Area of W_kappa0 = {1/kappa >= 1/kappa0} "
      "(column-wise; good to 1 % unless below_resolution)."),
    R("w_kappa0.rectangle_region_area", "length^2", "", "Area of the part of W_kappa0 a "
      "rectangle can use (each column's lowest run)."),
    R("w_kappa0.largest_inverse_condition.value", "-", r"$\max\,1/\kappa$",
      "The largest 1/kappa (at a corner of the reach: its limit there); W_kappa0 is found "
      "iff it exceeds 1/kappa0."),
    R("w_kappa0.largest_inverse_condition.x", "length", "$x$", "Where it is: x."),
    R("w_kappa0.largest_inverse_condition.y", "length", "$y$", "Its y."),
    R("w_kappa0.area_grid", "length^2", "", "Area of W_kappa0 counted on the grid."),
    R("w_kappa0.undescribed_area_grid", "length^2", "", "Grid area of W_kappa0 outside the "
      "boundary described."),
    R("w_kappa0.boundary[][][]", "length", "", "Closed boundary polylines [[x, y], ...]."),
    R("points[].x", "length", "$x$", "The given point's x."),
    R("points[].y", "length", "$y$", "Its y."),
    R("points[].inverse_condition", "-", _KAPPA, "1/kappa there (eq 7)."),
    R("points[].pressure_angles_deg[]", "deg", r"$\beta_i$", "Both pressure angles (eq 15)."),
    R("points[].min_pressure_angle_deg", "deg", _BETA_MIN, "The smaller of them."),
    R("points[].joint_angles_deg[]", "deg", r"$\theta_{1i}$",
      "Actuated joint angles [th_11, th_12] (eq 2; proximal arms)."),
    R("points[].joint_displacements[]", "length", "$q_i$", "Leg lengths or slider "
      "positions [q1, q2].", optional="for given points of telescopic legs or linear drives"),
    R("discretisation.grid.bounds[]", "length", "", "Grid bounds [x_min, x_max, y_min, y_max]."),
    R("discretisation.grid.points_per_axis", "-", "", "Grid nodes per axis."),
    R("discretisation.grid.step[]", "length", "", "Grid spacing [dx, dy]."),
    R("discretisation.w_kappa0.columns", "-", "", "Columns of the W_kappa0 search."),
    R("discretisation.w_kappa0.columns_added", "-", "", "Columns the W_kappa0 search added "
      "where the set is thin or ends."),
    R("discretisation.w_kappa0.rows", "-", "", "Rows of the W_kappa0 search."),
    R("discretisation.w_kappa0.x_half_span", "length", "", "Half-width in x of the search."),
)  # fmt: skip

_DESIGN = (
    R("delta", "-", r"$\delta$", "l2 / l1."),
    R("e", "l1", "$e$", "Half-distance of the actuated joints (eq 12)."),
    R("h", "l1", "$h$", "Height of the rectangle W_lambda."),
    R("b", "l1", "$b$", "Width of the rectangle (b = lambda h)."),
    R("H_prime", "l1", "$H'$", "Depth of the rectangle's top below the base."),
    R("S", "l1^2", "$S$", "Area of the rectangle, b h."),
    R("S_over_S_max", "-", r"$S/S_{\max}$", "S relative to the largest over the deltas."),
    R("mean_inverse_condition", "-", r"$\mathrm{mean}\,1/\kappa$",
      "Mean 1/kappa over the rectangle (eq 14)."),
    R("eta", "-", r"$\eta$", "Global index eta = (S/S_max) mean 1/kappa (eq 13)."),
    R("min_pressure_angle_deg", "deg", _BETA_MIN, "Least pressure angle over the rectangle."),
)  # fmt: skip

OPTIMISATION_RESULT_PATHS = (
    R("allowable_pressure_angle_deg", "deg", r"$[\beta]$", "The allowable pressure angle."),
    R("inverse_condition_limit", "-", r"$1/\kappa_0$", "The conditioning limit used."),
    R("inverse_condition_limit_delta", "-", r"$\delta$",
      "The delta where eq (17)'s 1/kappa0 is largest."),
    R("aspect_ratio", "-", r"$\lambda$", "The rectangle's aspect ratio b/h."),
    R("mean_mesh", "-", "", "Nodes per side of the mesh of the mean 1/kappa (eq 14)."),
    R("S_max", "l1^2", r"$S_{\max}$", "The largest rectangle area over the deltas."),
    *prefixed("sweep[]", _DESIGN),
    *prefixed("optimum", _DESIGN),
    R("optimum.l1", "l1", "$l_1$", "The proximal arm (1)."),
    R("optimum.l2", "l1", "$l_2$", "The distal arm (delta)."),
    R("optimum.H", "l1", "$H$", "H of eq (12)."),
    R("optimum.boundary_min_inverse_condition", "-", r"$\min\,1/\kappa$",
      "Least 1/kappa on the rectangle's boundary (the check that it lies in W_kappa0)."),
    R("window[]", "-", r"$\delta$", "[delta_lo, delta_hi]: where eta is within 0.001 of "
      "its maximum."),
    R("discretisation.deltas.range[]", "-", r"$\delta$", "The swept range of delta."),
    R("discretisation.deltas.step", "-", "", "The sweep's step."),
    R("discretisation.deltas.count", "-", "", "Deltas swept."),
    R("discretisation.deltas.delta", "-", r"$\delta$", "The one delta evaluated."),
    R("discretisation.mean_mesh[]", "-", "", "The mean's mesh."),
    R("discretisation.inverse_condition_limit.delta_range[]", "-", r"$\delta$",
      "Where eq (17)'s 1/kappa0 was maximised."),
    R("discretisation.rectangle.columns", "-", "", "Columns of the rectangle search."),
    R("discretisation.rectangle.rows", "-", "", "Rows of the rectangle search."),
    R("discretisation.rectangle.boundary_samples_per_edge", "-", "",
      "Samples per edge of the boundary check."),
    R("discretisation.window_tolerance", "-", "", "How close to the largest eta the window is."),
    R("discretisation.figure_9_mesh[]", "-", "", "Fig. 9's mesh."),
    R("discretisation.workspace_map_points_per_axis", "-", "", "Fig. 6's map, per axis."),
)  # fmt: skip
