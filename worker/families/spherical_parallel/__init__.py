"""Spherical parallel manipulators (Bai 2010): three job kinds.

The method, its conventions and the paper's errata: docs/methods/spherical-parallel.md.

``spm-conditioning-map``: one design's inverse kinematics and 1/kappa over a prescribed
workspace, with C_n (eq 25), mean(1/kappa^2) (eq 28), GCI (eq 24), the type-II measure
det(A), 1/kappa maps and torsion sweeps (Figs 6-7).
``spm-design-space``: the feasible (alpha1, alpha2) rectangle of eqs 16-19 per beta
(Fig. 5), optionally the conditioning index across one of them (Fig. 6).
``spm-optimisation``: the design maximising eq 28 over the design space (eqs 28-30,
Tables 1-3), its twins, every start and the paper's designs on the same samples.

Importing this package builds the three process definitions and nothing else: the job
modules (numpy, scipy, matplotlib) are imported when a job runs.
"""

from __future__ import annotations

from worker.contract import JobContext, JobOutcome
from worker.families.spherical_parallel.costs import (
    CONDITIONING_MAP_COST_LIMIT,
    CONDITIONING_MAP_SYNC_COST_LIMIT,
    CONDITIONING_MAP_TIME_LIMIT_S,
    COST_UNIT,
    DESIGN_OVERHEAD,
    DESIGN_SPACE_COST_LIMIT,
    DESIGN_SPACE_SYNC_COST_LIMIT,
    DESIGN_SPACE_TIME_LIMIT_S,
    LIMITED_WIDTH_COST,
    OPTIMISATION_COST_LIMIT,
    OPTIMISATION_TIME_LIMIT_S,
    conditioning_map_cost,
    design_space_cost,
    optimisation_cost,
)
from worker.families.spherical_parallel.examples import (
    CONDITIONING_MAP_EXAMPLES,
    CONDITIONING_MAP_PAPER_POINTS,
    DESIGN_SPACE_EXAMPLES,
    OPTIMISATION_EXAMPLES,
)
from worker.families.spherical_parallel.optimisation_spec import SCREEN_PER_START, OptimisationSpec
from worker.families.spherical_parallel.previews import CONDITIONING_MAP_PREVIEW
from worker.families.spherical_parallel.result_paths import (
    CONDITIONING_MAP_RESULT_PATHS,
    DESIGN_SPACE_RESULT_PATHS,
    OPTIMISATION_RESULT_PATHS,
)
from worker.families.spherical_parallel.specs import ConditioningMapSpec, DesignSpaceSpec
from worker.families.spherical_parallel.study import CONDITIONING_MAP_KERNEL
from worker.processes import FamilyInfo, ProcessDefinition, ProcessFile, data_files, figure_files

__all__ = ["CONDITIONING_MAP", "DESIGN_SPACE", "FAMILY", "OPTIMISATION", "PROCESSES"]


def _run_conditioning_map(spec: ConditioningMapSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.spherical_parallel.jobs.conditioning_map import run_conditioning_map

    return run_conditioning_map(spec, ctx)


def _run_design_space(spec: DesignSpaceSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.spherical_parallel.jobs.design_space import run_design_space

    return run_design_space(spec, ctx)


def _run_optimisation(spec: OptimisationSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.spherical_parallel.jobs.optimisation import run_optimisation

    return run_optimisation(spec, ctx)


def _limits(limit: int, time_s: float, sync: int, detail: str) -> str:
    text = f"Cost: {COST_UNIT}, {detail}; at most {limit:,}, {time_s:g} s per attempt"
    return text + (f"; up to {sync:,} may be answered synchronously." if sync else ".")


_SAMPLING = (
    "The workspace is a cone of opening 2T with a torsion range, sampled by default as "
    "docs/methods/spherical-parallel.md reads the paper's 4 x 12 x 3 = 144 orientations "
    "(equal-volume tilt cells), denser on request; every result reports the sampling used."
)
_INDICES = (
    "rms_inverse_condition is C_n of eq 25 (quadratic mean of 1/kappa), "
    "mean_square_inverse_condition its square, eq 28, the quantity the paper prints as "
    "'C_n'; gci is the arithmetic mean (eq 24); min_inverse_condition is over the samples, "
    "workspace_minimum over a boundary-inclusive grid of the closed workspace."
)

CONDITIONING_MAP = ProcessDefinition(
    id="spm-conditioning-map",
    version="1.1.0",  # torsion_sweeps: 1/kappa [-]
    preview=CONDITIONING_MAP_PREVIEW,
    result_paths=CONDITIONING_MAP_RESULT_PATHS,
    study_kernel=CONDITIONING_MAP_KERNEL,
    paper_points=CONDITIONING_MAP_PAPER_POINTS,
    title="Spherical parallel manipulator: conditioning over a workspace",
    method_doc="spherical-parallel",
    files=(
        *figure_files("inverse_condition_map", "1/kappa over tilt x azimuth at fixed torsions"),
        *figure_files("torsion_sweeps", "1/kappa along a full torsion turn"),
        ProcessFile(
            "conditioning_samples.csv", "Inverse kinematics and 1/kappa at the samples (CSV)"
        ),
        ProcessFile("conditioning_map.npz", "Conditioning map (NumPy arrays)"),
    ),
    description=(
        "For one design (alpha1, alpha2, beta, gamma; gamma = 0 is the coaxial 'active ball "
        "joint') and branch ((u_i x w_i) . v_i < 0 by default, eq 29): the inverse "
        "kinematics (eqs 11-12) at every workspace sample or which samples have none, "
        "1/kappa with the weighted norm of eqs 21-22, C_n, mean(1/kappa^2), GCI, min/max "
        "1/kappa, the type-II measure det(A) (eq 30), where the design sits in the design "
        "space, exact values at given orientations, 1/kappa maps over tilt x azimuth at "
        "chosen torsions (Fig. 6 style) and along full torsion turns (Fig. 7). "
        + _SAMPLING
        + " "
        + _INDICES
        + " "
        + _limits(
            CONDITIONING_MAP_COST_LIMIT,
            CONDITIONING_MAP_TIME_LIMIT_S,
            CONDITIONING_MAP_SYNC_COST_LIMIT,
            "samples + given orientations + map "
            "and sweep points + 22,464 for the closed-workspace minimum",
        )
    ),
    inputs_model=ConditioningMapSpec,
    run=_run_conditioning_map,
    examples=CONDITIONING_MAP_EXAMPLES,
    outputs={
        "design": "alpha1_deg, alpha2_deg, beta_deg, gamma_deg.",
        "branch": "The branch sign used (eq 29).",
        "workspace": "tilt_max_deg, cone_opening_deg, torsion_deg, full_turn.",
        "sampling": "The samples: n, counts, psi1/psi2/psi3 values (deg) and rules.",
        "indices": "rms_inverse_condition (C_n, eq 25), mean_square_inverse_condition "
        "(eq 28), gci (eq 24), min/max_inverse_condition, min_abs_det_a, all_real, "
        "samples, real_samples; null summaries unless every sample is reachable.",
        "workspace_minimum": "Least 1/kappa on the closed workspace (boundary included) and where.",
        "design_space": "f_min, f_max, D1_deg, D2_deg, margins_deg, feasible, on_edge (eq 19).",
        "type_ii_singularity": "min |det A|, min det(A)^2 (eq 30), where, det(A) range.",
        "inverse_kinematics": "samples, real, unreachable (indices, psi), and per sample "
        "(up to 2000) psi_deg, joint_angles_deg, inverse_condition, det_a.",
        "orientations": "Per given orientation, in order: psi_deg, real, joint_angles_deg, "
        "condition_number (kappa), inverse_condition, det_a.",
        "maps": "The tilt x azimuth grid and, per torsion, min/max 1/kappa.",
        "torsion_sweeps": "Per [psi1, psi2]: min (and where) and max 1/kappa over a turn.",
        "definitions": "What each measure is, with the paper's equation numbers.",
        "data": "Names of the CSV (one row per sample) and NPZ artifacts.",
    },
    cost=conditioning_map_cost,
    cost_limit=CONDITIONING_MAP_COST_LIMIT,
    seconds_per_cost=1e-6,
    cost_unit=COST_UNIT,
    time_limit_s=CONDITIONING_MAP_TIME_LIMIT_S,
    sync_cost_limit=CONDITIONING_MAP_SYNC_COST_LIMIT,
)

DESIGN_SPACE = ProcessDefinition(
    id="spm-design-space",
    version="1.1.0",  # index_map: contour lines broken only under their labels
    result_paths=DESIGN_SPACE_RESULT_PATHS,
    title="Spherical parallel manipulator: design space for a prescribed workspace",
    method_doc="spherical-parallel",
    files=(
        *figure_files("design_space", "Sub-design spaces in the a1-a2 plane"),
        *figure_files("index_map", "mean(1/kappa^2) over one sub-design space"),
        *data_files("design_space", "Design space per beta"),
    ),
    description=(
        "For each beta (a list or a range) and gamma (or gamma = beta with identical "
        "platforms): f_min and f_max of f_i = n_i . v_i over the continuous workspace and "
        "the feasible rectangle |alpha1 - alpha2| <= acos(-f_min), |alpha1 + alpha2 - 180| "
        "<= acos(f_max) (eqs 16-19), or that it is degenerate (a line) or empty; the "
        "sub-design spaces in the alpha1-alpha2 plane (Fig. 5) and optionally "
        "mean(1/kappa^2) across one of them (Fig. 6). "
        + _limits(
            DESIGN_SPACE_COST_LIMIT,
            DESIGN_SPACE_TIME_LIMIT_S,
            DESIGN_SPACE_SYNC_COST_LIMIT,
            "betas x (1 for a full turn, "
            f"{LIMITED_WIDTH_COST:,} for a limited torsion range) + index-map designs x "
            f"(samples + {DESIGN_OVERHEAD})",
        )
    ),
    inputs_model=DesignSpaceSpec,
    run=_run_design_space,
    examples=DESIGN_SPACE_EXAMPLES,
    outputs={
        "workspace": "The prescribed workspace.",
        "identical_platforms": "Whether gamma = beta.",
        "gamma_deg": "The gamma used (null with identical platforms).",
        "method": "How f_min and f_max were found on the continuous workspace.",
        "designs": "One per beta, in order: beta_deg, gamma_deg, f_min, f_max, D1_deg, D2_deg, "
        "status ('rectangle', 'degenerate', 'empty'), rectangle (bounds, corners, alpha ranges, "
        "area).",
        "summary": "Counts, the degenerate and empty betas, the beta with the widest rectangle.",
        "index_map": "With index_map: the grid, min/max mean(1/kappa^2) and the best grid "
        "designs with their indices; else null.",
        "sampling": "The samples of the index map, or null.",
        "data": "Names of the CSV (one row per beta) and NPZ artifacts.",
    },
    cost=design_space_cost,
    cost_limit=DESIGN_SPACE_COST_LIMIT,
    seconds_per_cost=6e-7,
    cost_unit=COST_UNIT,
    time_limit_s=DESIGN_SPACE_TIME_LIMIT_S,
    sync_cost_limit=DESIGN_SPACE_SYNC_COST_LIMIT,
)

OPTIMISATION = ProcessDefinition(
    id="spm-optimisation",
    version="1.1.0",  # index_map: contour lines broken only under labels; torsion_sweeps [-]
    result_paths=OPTIMISATION_RESULT_PATHS,
    title="Spherical parallel manipulator: optimum design for a prescribed workspace",
    method_doc="spherical-parallel",
    files=(
        *figure_files("index_map", "mean(1/kappa^2) over the optimum's design space"),
        *figure_files("starts", "Final mean(1/kappa^2) of every start"),
        *figure_files("torsion_sweeps", "1/kappa of the optimum along torsion turns"),
        ProcessFile("optimisation_starts.csv", "Every optimisation start (CSV)"),
        ProcessFile("optimisation.npz", "Optimisation (NumPy arrays)"),
    ),
    description=(
        "Maximises mean(1/kappa^2) over the workspace samples (eq 28) by nonlinear least "
        "squares from several seeded starts in the design space, over the free parameters "
        "(alpha1, alpha2, beta, optionally gamma; identical_platforms ties gamma to beta), "
        "each start the best of a seeded screen of the design space, "
        "feasible on the continuous workspace by construction (eq 19: infeasible designs "
        "are never scored), on one branch (eq 29), optionally with det(A)^2 >= lambda "
        "(eq 30). Reports the optimum with its indices and its twin optima, every start "
        "(converged or not, with the solver's message), the evaluations spent, and for the "
        "paper's examples its designs scored on the same samples (notes say where the "
        "optimum beats them). "
        + _SAMPLING
        + " "
        + _limits(
            OPTIMISATION_COST_LIMIT,
            OPTIMISATION_TIME_LIMIT_S,
            0,
            "starts x (max_evaluations_per_start x (1 + free variables) + "
            f"{SCREEN_PER_START} screened candidates) x (samples + "
            f"{DESIGN_OVERHEAD}, + {LIMITED_WIDTH_COST:,} when a limited torsion range "
            "meets a free beta or gamma) + the figures",
        )
    ),
    inputs_model=OptimisationSpec,
    run=_run_optimisation,
    examples=OPTIMISATION_EXAMPLES,
    outputs={
        "success": "Whether some start ended on a feasible design.",
        "message": "The solver's message for the best start (or why there is none).",
        "optimum": "alpha1_deg..gamma_deg, branch, the indices (as in spm-conditioning-map), "
        "workspace_minimum, design_space (margins, on_edge), the start it came from and "
        "twins (designs scoring the same: supplementary links, and for a full turn the "
        "180 - beta twins); null without a feasible design.",
        "starts": "Every start: start and end designs, solver variables, converged, status, "
        "message, nfev, evaluations, feasible, mean_square_inverse_condition, the end "
        "design's indices (null unless feasible), best.",
        "evaluations": "Residual evaluations spent over all starts (finite differences "
        "included) and the screening of the starts.",
        "screening": "How the starts were seeded from the design space: candidates per start, "
        "candidates, designs scored, rule.",
        "budget": "starts and max_evaluations_per_start.",
        "free": "The free parameters.",
        "held_deg": "The held parameters (deg).",
        "identical_platforms": "Whether gamma = beta.",
        "bounds_deg": "Search ranges of a free beta/gamma.",
        "variables": "The solver's variables (s, t or u for the link angles; beta, gamma).",
        "solver": "How the least-squares problem is posed and solved.",
        "branch": "The branch sign (eq 29).",
        "seed": "The seed of the starts.",
        "singularity_tolerance": "lambda of eq 30, or null.",
        "workspace": "The prescribed workspace.",
        "sampling": "The samples used (the n of eq 28).",
        "paper": "For the paper's Examples I-III: its designs with their printed value and "
        "their indices on the same samples, and whether the optimum beats each; else null.",
        "data": "Names of the CSV (one row per start) and NPZ artifacts.",
    },
    cost=optimisation_cost,
    cost_limit=OPTIMISATION_COST_LIMIT,
    seconds_per_cost=3e-7,
    cost_unit=COST_UNIT,
    time_limit_s=OPTIMISATION_TIME_LIMIT_S,
)

#: Who this family is: the tag its operations are listed under, and its paper.
FAMILY = FamilyInfo(
    name="spherical_parallel",
    tag="Spherical parallel manipulators",
    description=(
        "Bai 2010: kinematics, conditioning over an orientation workspace, the design "
        "space and the optimum design."
    ),
    paper="Bai 2010",
)

#: This family's processes, in the order GET /v1/processes lists them.
PROCESSES = (
    CONDITIONING_MAP,
    DESIGN_SPACE,
    OPTIMISATION,
)
