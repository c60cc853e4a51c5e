"""Three-link planar serial arms (Patel & Sobh): three job kinds.

The method, its conventions and the paper's errata: docs/methods/planar-serial.md.

``planar3r-dexterity-map``: d_z and D = d_z/3 over a grid for given links, with the
paper's regions, the exact full-dexterity bands, task points and a trajectory.
``planar3r-synthesis``: link lengths from task points or a trajectory by eqs (10)-(11),
checked in the paper's three cases.
``planar3r-design``: link lengths (and the base) chosen for the task under its joint
limits by a multi-start global search over the exact d_z, against the paper's rule.

Importing this package builds the two process definitions and nothing else: the job
modules (numpy maps, matplotlib figures) are imported when a job runs.
"""

from __future__ import annotations

from worker.contract import JobContext, JobOutcome
from worker.families.planar_serial.costs import (
    COST_LIMIT,
    MIN_DESIGN_TIME_LIMIT_S,
    SYNC_COST_LIMIT,
    TIME_LIMIT_S,
    design_cost,
    design_time_limit,
    dexterity_map_cost,
    synthesis_cost,
)
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.examples import (
    DESIGN_EXAMPLES,
    DEXTERITY_MAP_EXAMPLES,
    SYNTHESIS_EXAMPLES,
)
from worker.families.planar_serial.previews import DEXTERITY_MAP_CHART, DEXTERITY_MAP_PREVIEW
from worker.families.planar_serial.result_paths import (
    DESIGN_RESULT_PATHS,
    DEXTERITY_MAP_RESULT_PATHS,
    SYNTHESIS_RESULT_PATHS,
)
from worker.families.planar_serial.specs import DexterityMapSpec, SynthesisSpec
from worker.families.planar_serial.study import DEXTERITY_MAP_KERNEL
from worker.processes import FamilyInfo, ProcessDefinition, ProcessFile, data_files, figure_files

__all__ = ["DESIGN", "DEXTERITY_MAP", "FAMILY", "PROCESSES", "SYNTHESIS"]


def _run_dexterity_map(spec: DexterityMapSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.planar_serial.jobs.dexterity_map import run_dexterity_map

    return run_dexterity_map(spec, ctx)


def _run_synthesis(spec: SynthesisSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.planar_serial.jobs.synthesis import run_synthesis

    return run_synthesis(spec, ctx)


def _run_design(spec: DesignSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.planar_serial.jobs.optimal_links import run_design

    return run_design(spec, ctx)


_LIMITS_TEXT = (
    f"Cost: {{unit}}; at most {COST_LIMIT:,} (e.g. a 2001 x 2001 grid sampled every "
    f"0.5°), {TIME_LIMIT_S:g} s per attempt."
)

DEXTERITY_MAP = ProcessDefinition(
    id="planar3r-dexterity-map",
    # 1.1.0: radial_section: the curve stops where the arm cannot reach; 2.0.0: under
    # joint limits 'regions' and 'full_dexterity_bands' are the limited arm's along the
    # radial section's ray (the unlimited arm's moved under areas.unlimited_reference);
    # summary.warnings and unreachable_task_points (issue 26)
    version="2.0.0",
    preview=DEXTERITY_MAP_PREVIEW,
    data_chart=DEXTERITY_MAP_CHART,
    result_paths=DEXTERITY_MAP_RESULT_PATHS,
    title="Three-link planar arm: dexterity map",
    method_doc="planar-serial",
    files=(
        *figure_files("heatmap", "Dexterity d_z over the workspace"),
        *figure_files("surface", "Dexterity d_z, 3-D surface"),
        *figure_files("radial_section", "Dexterity d_z along a ray from the base"),
        *data_files("dexterity_map", "Dexterity map"),
    ),
    description=(
        "Orientation dexterity d_z (0..1) and dexterity index D = d_z/3 (Patel & Sobh "
        "eqs 2-5) at every node of a grid, for links [l1, l2, l3] from the base. Fully "
        "revolute joints: the exact closed form (docs/methods/planar-serial.md). With "
        "joint limits, method 'exact-events' (default): the feasible orientation arcs "
        "between closed-form events (a joint at a limit, the wrist on the edge of the "
        "two-link annulus), both elbow branches, exact to rounding; method "
        "'orientation-sampling': orientations sampled every orientation_step_deg, task "
        "points refined by bisection. Reports the paper's four regions next to the exact "
        "bands of full dexterity (under joint limits the limited arm's, along the radial "
        "section's ray), reachable and fully dexterous areas (of the joint-limited arm "
        "under limits), d_z at task points and along a trajectory (eq 4 mean), CSV/NPZ "
        "data and heat-map, 3-D surface and radial-section plots; an empty map or a task "
        "point out of reach is a warning. "
        + _LIMITS_TEXT.format(
            unit="grid points x orientations tested per point (1 without joint limits, "
            "at most 21 sub-arcs with exact events, the samples with orientation sampling)"
        )
    ),
    inputs_model=DexterityMapSpec,
    run=_run_dexterity_map,
    examples=DEXTERITY_MAP_EXAMPLES,
    outputs={
        "links": "The links [l1, l2, l3].",
        "joint_limits_deg": "The joint limits used, or null.",
        "length_unit": "The length unit.",
        "method": "'exact-closed-form' (revolute joints), or under joint limits "
        "'exact-events' or 'orientation-sampling' (the input method).",
        "discretisation": "Grid (bounds, points_per_axis, step), effective orientation step "
        "and sample count (sampling) or events per point and unused_inputs (exact events), "
        "elbow branches, method for task points and trajectory samples, radial section.",
        "regions": "The paper's regions 1-4 (distance ranges), its claim for each, and the "
        "exact finding (fully dexterous bands inside, d_z range along a ray); under joint "
        "limits the limited arm's along the radial section's ray (exact events).",
        "full_dexterity_bands": "Exact radii [[r0, r1], ...] where d_z = 1: for revolute "
        "joints at every angle; under joint limits the limited arm's along the radial "
        "section's ray (possibly none).",
        "areas": "Reachable and fully dexterous areas: exact for revolute joints; under joint "
        "limits the limited arm's, counted on the map, with unlimited_reference (the "
        "unlimited arm's areas, full_dexterity_bands and regions); their grid estimates, "
        "the cell area and how they were obtained (method).",
        "summary": "d_z_max, mean d_z and D over reachable nodes, node counts, "
        "unreachable_task_points (labels of task points with d_z = 0) and warnings (an "
        "empty map, task points out of reach; also the first notes).",
        "task_points": "Per task point, in order: label, x, y, distance, d_z, D, region.",
        "trajectory": "Along the sampled trajectory: samples, d_z_mean, D_mean (eq 4), "
        "d_z_min, fully_dexterous_fraction; null without a trajectory.",
        "data": "Names of the CSV and NPZ artifacts holding the map.",
    },
    cost=dexterity_map_cost,
    cost_limit=COST_LIMIT,
    seconds_per_cost=5e-7,
    seconds_per_run=0.015,  # the checks of its links and joint limits
    sync_cost_limit=SYNC_COST_LIMIT,
    time_limit_s=TIME_LIMIT_S,
    study_kernel=DEXTERITY_MAP_KERNEL,
)

SYNTHESIS = ProcessDefinition(
    id="planar3r-synthesis",
    version="1.1.0",  # synthesis_cases: lengths to 4 digits, with their unit
    result_paths=SYNTHESIS_RESULT_PATHS,
    title="Three-link planar arm: link lengths from task points or a trajectory",
    method_doc="planar-serial",
    files=(
        *figure_files("synthesis_cases", "d_z of the design in the paper's cases"),
        ProcessFile("synthesis_cases.npz", "d_z maps of the cases (NumPy arrays)"),
    ),
    description=(
        "Patel & Sobh's synthesis: the exact distance range [d_min, d_max] of the task "
        "points or trajectory from the base (optionally rounded outward, as the paper "
        "does), l1 = (d_max + l3)/2 + 1 and l2 = (d_max + l3)/2 (eqs 10-11), Grashof's "
        "criterion at d_min and d_max, the paper's claimed conditions next to the real "
        "condition for full dexterity (docs/methods/planar-serial.md), and d_z at the task "
        "points and along the trajectory in the paper's cases: 1 ideal, 2 with l2 and l3 "
        "swapped, 3 under joint limits (if given). Notes flag task points short of full "
        "dexterity and, listed again under paper_errata, the paper's errata when the inputs "
        "are its examples. "
        + _LIMITS_TEXT.format(
            unit="grid points x (2 + orientations tested per point in Case 3, if joint "
            "limits are given)"
        )
    ),
    inputs_model=SynthesisSpec,
    run=_run_synthesis,
    examples=SYNTHESIS_EXAMPLES,
    outputs={
        "distance_source": "'trajectory' or 'task_points': what set d_min and d_max.",
        "d_min": "Exact smallest distance from the base.",
        "d_max": "Exact largest distance from the base.",
        "d_min_at": "Where d_min is attained, [x, y].",
        "d_max_at": "Where d_max is attained, [x, y].",
        "round_distances": "Whether d_min/d_max were rounded outward before eqs (10)-(11).",
        "d_min_used": "d_min fed to the design.",
        "d_max_used": "d_max fed to the design (eqs 10-11).",
        "l3": "The chosen last link.",
        "links": "The design [l1, l2, l3].",
        "grashof": "Grashof's criterion on the four-bar (l1, l2, l3, d) at d_min and d_max.",
        "paper_conditions": "The paper's claimed orderings at d_min and d_max, evaluated.",
        "full_dexterity_bands": "Exact radii where the design has d_z = 1.",
        "full_dexterity_condition": "The real condition: [d_min, d_max] inside "
        "[l3 + |l1 - l2|, l1 + l2 - l3].",
        "task_points": "Case 1 evaluation of each task point: label, x, y, distance, d_z, "
        "D, region.",
        "cases": "Cases 1-3: links, limits, bands and areas, task points, trajectory "
        "summary, whether all task points are fully dexterous.",
        "discretisation": "Plot grid, Case 3's orientations (sampling or exact events), "
        "task-point method.",
        "length_unit": "The length unit.",
    },
    cost=synthesis_cost,
    cost_limit=COST_LIMIT,
    seconds_per_cost=6e-8,
    time_limit_s=TIME_LIMIT_S,
)

DESIGN = ProcessDefinition(
    id="planar3r-design",
    result_paths=DESIGN_RESULT_PATHS,
    title="Three-link planar arm: link lengths designed for the task under joint limits",
    method_doc="planar-serial",
    files=(
        *figure_files("design_maps", "d_z of the paper's rule and the optimum"),
        *figure_files("convergence", "Best design per generation of every start"),
        ProcessFile(
            "design_maps.npz", "d_z maps of the paper's rule and the optimum (NumPy arrays)"
        ),
        ProcessFile("convergence.csv", "Best design per start and generation (CSV)"),
    ),
    description=(
        "Link lengths l1 and l2 (and, with base_box, the base position) chosen for task "
        "points and/or a trajectory under the joint limits the arm really has, the tool "
        "link l3 held (input l3; default the paper rule's l3 for total_length_max), or l3 "
        "designed too within link_bounds: objective 'max_min_dz' maximises the smallest "
        "d_z over the task, 'min_length' finds the shortest arm keeping d_z >= dz_target "
        "everywhere, within total_length_max. d_z is exact (closed-form events under "
        "joint limits); the search is 'starts' independent starts (default 8) of seeded "
        "differential evolution (every generation run), each polished by Nelder-Mead, "
        "deterministic for a seed; the best is kept, and success needs at least two starts "
        "agreeing on the best score within 1e-4. Reports the optimum with d_z at every "
        "task point and along the trajectory, the paper's rule (eqs 10-11) under the same "
        "limits and the improvement over it, the convergence (every start's best, "
        "evaluations, best per generation, success, message), the two d_z maps and the "
        "convergence curves (docs/methods/planar-serial.md). "
        + "Cost: designs evaluated x task points and trajectory samples x orientations "
        "tested per point (1 without joint limits, at most 21 sub-arcs under them), plus "
        "3,400 per evaluation of d_z and the two maps; at most "
        f"{COST_LIMIT:,}. Time limit per attempt: in proportion to the cost, from "
        f"{MIN_DESIGN_TIME_LIMIT_S:g} s to {TIME_LIMIT_S:g} s at the cost limit."
    ),
    inputs_model=DesignSpec,
    run=_run_design,
    examples=DESIGN_EXAMPLES,
    outputs={
        "objective": "'max_min_dz' or 'min_length'.",
        "dz_target": "The target d_z of 'min_length' (null for 'max_min_dz').",
        "joint_limits_deg": "The joint limits used, or null.",
        "method": "How d_z was computed: 'exact-events' (joint limits) or 'exact-closed-form'.",
        "optimum": "links, base, min_dz, mean_dz, total_length, meets_target (min_length), "
        "task_points [{label, x, y, d_z}], trajectory (samples, d_z_mean, D_mean, d_z_min, "
        "fully_dexterous_fraction) or null.",
        "paper_rule": "The same record for eqs (10)-(11) with the base at the origin and the "
        "same limits, with d_min_used, d_max_used and how l3 was chosen; null if no l3 fits.",
        "improvement": "max_min_dz: gain in min_dz (absolute and relative); min_length: "
        "length saved and whether each design meets the target. Null without paper_rule.",
        "convergence": "success (at least two starts agree on the best score within "
        "agreement_tol, and min_length's target is met), message, seed, starts [{start, "
        "seed, score, min_dz, total_length, meets_target, links, base, agrees_with_best, "
        "evaluations}], kept_start, agreeing_starts, agreement_tol, evaluations (all "
        "starts), generations, best_per_generation [{generation, min_dz, total_length, "
        "score}] of the kept start, its global_search and polish details.",
        "search_space": "link_bounds (defaults resolved; a held l3 as [l3, l3]), l3_held "
        "(null when designed), l3_chosen, total_length_max, base_box, free_variables.",
        "evaluation_points": "How many task points and trajectory samples the objective uses.",
        "length_unit": "The length unit.",
    },
    cost=design_cost,
    cost_limit=COST_LIMIT,
    time_limit_s=TIME_LIMIT_S,
    attempt_time_limit=design_time_limit,
    version="2.0.0",
)

#: Who this family is: the tag its operations are listed under, and its paper.
FAMILY = FamilyInfo(
    name="planar_serial",
    tag="Three-link planar serial arms",
    description=(
        "Patel & Sobh: synthesis from task points or a trajectory, dexterity maps, joint limits."
    ),
    paper="Patel & Sobh 2012",
)

#: This family's processes, in the order GET /v1/processes lists them.
PROCESSES = (
    DEXTERITY_MAP,
    SYNTHESIS,
    DESIGN,
)
