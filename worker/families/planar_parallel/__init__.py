"""2-DOF planar parallel robots (Huang et al. 2004): two job kinds.

The method, its conventions and the paper's errata: docs/methods/planar-parallel.md.

``planar2dof-conditioning-map``: 1/kappa, the pressure angles and beta_min over a grid
for one robot of Fig. 1 in one working mode, with W_kappa0 and given points.
``planar2dof-optimisation``: the paper's design of the proximal-arm robot: 1/kappa0 from
an allowable pressure angle, the largest rectangle in W_kappa0 and eta over delta.

Importing this package builds the two process definitions and nothing else: the job
modules (numpy, scipy, matplotlib) are imported when a job runs.
"""

from __future__ import annotations

from worker.contract import JobContext, JobOutcome
from worker.families.planar_parallel.costs import (
    CONDITIONING_MAP_COST_LIMIT,
    CONDITIONING_MAP_SYNC_COST_LIMIT,
    CONDITIONING_MAP_TIME_LIMIT_S,
    COST_UNIT,
    OPTIMISATION_COST_LIMIT,
    OPTIMISATION_TIME_LIMIT_S,
    RECTANGLE_SEARCH_COST,
    conditioning_map_cost,
    optimisation_cost,
)
from worker.families.planar_parallel.examples import (
    CONDITIONING_MAP_EXAMPLES,
    OPTIMISATION_EXAMPLES,
    OPTIMISATION_PAPER_POINTS,
)
from worker.families.planar_parallel.previews import (
    CONDITIONING_MAP_CHART,
    CONDITIONING_MAP_PREVIEW,
)
from worker.families.planar_parallel.result_paths import (
    CONDITIONING_MAP_RESULT_PATHS,
    OPTIMISATION_RESULT_PATHS,
)
from worker.families.planar_parallel.specs import ConditioningMapSpec, OptimisationSpec
from worker.families.planar_parallel.study import CONDITIONING_MAP_KERNEL
from worker.processes import FamilyInfo, ProcessDefinition, ProcessFile, data_files, figure_files

__all__ = ["CONDITIONING_MAP", "FAMILY", "OPTIMISATION", "PROCESSES"]


def _run_conditioning_map(spec: ConditioningMapSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.planar_parallel.jobs.conditioning_map import run_conditioning_map

    return run_conditioning_map(spec, ctx)


def _run_optimisation(spec: OptimisationSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.planar_parallel.jobs.optimisation import run_optimisation

    return run_optimisation(spec, ctx)


CONDITIONING_MAP = ProcessDefinition(
    id="planar2dof-conditioning-map",
    preview=CONDITIONING_MAP_PREVIEW,
    data_chart=CONDITIONING_MAP_CHART,
    # 1.1: figures: a contour label only where it sits on its line.
    # 1.2: W_kappa0 found and measured at any size (thin sets, sets between columns);
    # largest_inverse_condition and below_resolution added.
    version="1.2.0",
    result_paths=CONDITIONING_MAP_RESULT_PATHS,
    title="2-DOF planar parallel robot: conditioning map",
    method_doc="planar-parallel",
    files=(
        *figure_files("inverse_condition_map", "Conditioning index 1/kappa (Fig. 4)"),
        *figure_files("pressure_angle_map", "Minimum pressure angle beta_min (Fig. 5)"),
        *data_files("conditioning_map", "Conditioning map, one row per grid node"),
    ),
    description=(
        "For a mirror-symmetric 2-DOF parallel robot of Huang et al.'s Fig. 1 (proximal "
        "arms, telescopic legs or linear drives) in one working mode: reachability, the "
        "conditioning index 1/kappa (eq 7) and both pressure angles (eq 15) with their "
        "minimum beta_min at every node of a grid; the boundary and area of W_kappa0 = "
        "{1/kappa >= 1/kappa0} for a given limit; the isotropic point; exact values at "
        "given points; CSV/NPZ data and contour plots of 1/kappa and beta_min (Figs 4-5). "
        f"Cost: {COST_UNIT} = grid points + given points (+ "
        "801 x 321 for the W_kappa0 boundary); at most "
        f"{CONDITIONING_MAP_COST_LIMIT:,} (a 2001 x 2001 grid), "
        f"{CONDITIONING_MAP_TIME_LIMIT_S:g} s per attempt."
    ),
    inputs_model=ConditioningMapSpec,
    run=_run_conditioning_map,
    examples=CONDITIONING_MAP_EXAMPLES,
    outputs={
        "actuation": "The robot type.",
        "l1": "Proximal link length as given (proximal-arm type).",
        "l2": "Distal link length as given (null if not given).",
        "e": "Half-distance of the actuated joints: given, or by eq (12); null for linear "
        "drives without it.",
        "delta": "l2 / l1 (proximal-arm type), else null.",
        "architecture": "'isotropic' (e by eq 12) or 'given'.",
        "working_mode": "The working mode [sgn1, sgn2].",
        "length_unit": "The length unit.",
        "isotropic_point": "x, y, inverse_condition, min_pressure_angle_deg, isotropic "
        "(1/kappa = 1) and degenerate (links folded, A singular): the closed form when one "
        "exists, else the best point on x = 0 below the base; null if 1/kappa is 0 there.",
        "summary": "Reachable node count and grid area; min/max/mean of 1/kappa and of "
        "beta_min (deg) over reachable nodes.",
        "w_kappa0": "With a limit: inverse_condition_limit; found (W_kappa0 is not empty: "
        "the largest 1/kappa exceeds the limit); area (all of W_kappa0) and "
        "rectangle_region_area (the lowest run of each column, where the paper's rectangle "
        "lives), column-wise, good to 1 % for a set of at least 1e-4 of the reachable area "
        "on the grid; area_grid; undescribed_area_grid; largest_inverse_condition (value, "
        "x, y; null if nothing was searched); below_resolution (the set is smaller than "
        "that); boundary (closed polylines [[x, y], ...] around the lowest runs) and "
        "message; else null.",
        "points": "Per given point, in order: x, y, reachable, inverse_condition, "
        "pressure_angles_deg, min_pressure_angle_deg, joint_angles_deg (proximal arm), "
        "joint_displacements (leg lengths or slider positions).",
        "discretisation": "Grid (bounds, points_per_axis, step), the W_kappa0 search "
        "(columns, rows, span), how points and the isotropic point are evaluated.",
        "data": "Names of the CSV and NPZ artifacts holding the map.",
    },
    cost=conditioning_map_cost,
    cost_limit=CONDITIONING_MAP_COST_LIMIT,
    sync_cost_limit=CONDITIONING_MAP_SYNC_COST_LIMIT,
    seconds_per_cost=1.1e-6,
    cost_unit=COST_UNIT,
    time_limit_s=CONDITIONING_MAP_TIME_LIMIT_S,
    study_kernel=CONDITIONING_MAP_KERNEL,
)

OPTIMISATION = ProcessDefinition(
    id="planar2dof-optimisation",
    version="1.1.0",  # figures: a contour label only where it sits on its line
    result_paths=OPTIMISATION_RESULT_PATHS,
    paper_points=OPTIMISATION_PAPER_POINTS,
    title="2-DOF planar parallel robot: optimum design (proximal arms)",
    method_doc="planar-parallel",
    files=(
        *figure_files("conditioning_limit", "1/kappa0 against [beta] and delta (Fig. 7)"),
        *figure_files("design_indices", "S/S_max, mean 1/kappa and eta against delta (Fig. 8)"),
        *figure_files("normalised_rectangle", "1/kappa and beta_min over the rectangle (Fig. 9)"),
        *figure_files("rectangle_workspace", "The rectangle inside W_kappa0 (Fig. 6)"),
        ProcessFile("sweep.csv", "The delta sweep, one row per delta (CSV)"),
        ProcessFile("optimisation.npz", "The sweep and the figures' arrays (NumPy arrays)"),
    ),
    description=(
        "Huang et al.'s design of the proximal-arm robot with the isotropic architecture of "
        "eq (12) (l1 = 1, l2 = delta): the conditioning limit 1/kappa0 from an allowable "
        "pressure angle [beta] (eq 17 + eq 7, maximised over delta; Fig. 7) or as given; "
        "for each delta of a sweep (or one delta) the largest rectangle W_lambda of aspect "
        "lambda = b/h inside W_kappa0 (Fig. 6), the mean 1/kappa over it (eq 14) and eta = "
        "(S/S_max) mean (eq 13; Fig. 8); the optimum, the window of delta where eta is "
        "within 0.001 of its maximum, 1/kappa and beta_min over the rectangle (Fig. 9). "
        f"Cost: {COST_UNIT} = deltas x (mean_mesh² + {RECTANGLE_SEARCH_COST:,} for the "
        f"rectangle search); at most {OPTIMISATION_COST_LIMIT:,} (about 12 times the "
        f"default sweep), {OPTIMISATION_TIME_LIMIT_S:g} s per attempt."
    ),
    inputs_model=OptimisationSpec,
    run=_run_optimisation,
    examples=OPTIMISATION_EXAMPLES,
    outputs={
        "allowable_pressure_angle_deg": "[beta] as given, or null.",
        "inverse_condition_limit": "1/kappa0 used: from eq (17) + eq (7) (maximised over "
        "delta) or as given.",
        "inverse_condition_limit_source": "'eq (17) + eq (7), maximised over delta' or 'given'.",
        "inverse_condition_limit_delta": "The delta where eq (17)'s 1/kappa0 is largest, or null.",
        "aspect_ratio": "lambda = b/h.",
        "mean_mesh": "Nodes per side of the mesh of the mean 1/kappa (eq 14).",
        "evaluation": "'sweep' or 'single-delta'.",
        "S_max": "The largest rectangle area over the swept deltas (single delta: over the "
        "paper's [1, 2.5] at step 0.01, and the delta).",
        "sweep": "One entry per delta: delta, e, h, b, H_prime, S, S_over_S_max, "
        "mean_inverse_condition, eta, min_pressure_angle_deg, found.",
        "optimum": "The design of largest eta (single delta: the design evaluated): delta, e, "
        "b, h, H_prime, S, mean_inverse_condition, eta, min_pressure_angle_deg, "
        "S_over_S_max, l1, l2, H (eq 12), the rectangle's boundary check; null if none.",
        "window": "[delta_lo, delta_hi]: the deltas around the optimum where eta is within "
        "0.001 of its maximum; null for a single delta.",
        "discretisation": "Deltas (range, step, count), the mean mesh, S_max's range, the "
        "limit's and the rectangle's search settings, the figures' meshes.",
        "data": "Names of the CSV (the sweep) and NPZ (sweep and figures' arrays) artifacts.",
    },
    cost=optimisation_cost,
    cost_limit=OPTIMISATION_COST_LIMIT,
    seconds_per_cost=1e-7,
    cost_unit=COST_UNIT,
    time_limit_s=OPTIMISATION_TIME_LIMIT_S,
)

#: Who this family is: the tag its operations are listed under, and its paper.
FAMILY = FamilyInfo(
    name="planar_parallel",
    tag="2-DOF planar parallel robots",
    description=(
        "Huang et al. 2004: conditioning and pressure-angle maps, the workspace bounded "
        "by a conditioning limit, the largest rectangle, η, the optimum."
    ),
    paper="Huang et al. 2004",
)

#: This family's processes, in the order GET /v1/processes lists them.
PROCESSES = (
    CONDITIONING_MAP,
    OPTIMISATION,
)
