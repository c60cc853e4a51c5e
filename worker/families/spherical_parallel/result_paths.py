"""The numeric result paths of the SPM processes: units, symbols, meanings
(:mod:`worker.result_paths`; every angle in degrees)."""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R
from worker.result_paths import prefixed

__all__ = [
    "CONDITIONING_MAP_RESULT_PATHS",
    "DESIGN_SPACE_RESULT_PATHS",
    "OPTIMISATION_RESULT_PATHS",
]

_KAPPA = r"$1/\kappa$"
_MEAN_SQUARE = r"$\mathrm{mean}(1/\kappa^2)$"
_UNREACHABLE = "when some workspace samples have no inverse kinematics"

_ANGLES = (
    R("alpha1_deg", "deg", r"$\alpha_1$", "Base-side link angle."),
    R("alpha2_deg", "deg", r"$\alpha_2$", "Platform-side link angle."),
    R("beta_deg", "deg", r"$\beta$", "Mobile pyramid half-angle."),
    R("gamma_deg", "deg", r"$\gamma$", "Base pyramid half-angle (0: the coaxial active ball "
      "joint)."),
)  # fmt: skip
_BRANCH = R("branch", "-", "", "The branch sign kept on every leg (eq 29).")
_INDICES = (
    R("rms_inverse_condition", "-", "$C_n$", "C_n: the quadratic mean of 1/kappa over the "
      "samples (eq 25)."),
    R("mean_square_inverse_condition", "-", _MEAN_SQUARE, "mean(1/kappa^2) over the samples "
      "(eq 28): what the paper prints as C_n."),
    R("gci", "-", r"$\mathrm{GCI}$", "Global conditioning index: the mean of 1/kappa (eq 24)."),
    R("min_inverse_condition", "-", r"$\min\,1/\kappa$", "Least 1/kappa over the samples."),
    R("max_inverse_condition", "-", r"$\max\,1/\kappa$", "Largest 1/kappa over the samples."),
    R("min_abs_det_a", "-", r"$\min\,|\det A|$", "Least |det A| over the samples (eq 30)."),
    R("samples", "-", "$n$", "Workspace samples."),
    R("real_samples", "-", "", "Samples with real inverse kinematics."),
    _BRANCH,
)  # fmt: skip
_WORKSPACE = (
    R("tilt_max_deg", "deg", "$T$", "Largest tilt of the prescribed cone."),
    R("cone_opening_deg", "deg", "$2T$", "Opening of the cone."),
    R("torsion_deg[]", "deg", r"$\psi_3$", "The torsion range [lo, hi]."),
)
_SAMPLING = (
    R("n", "-", "$n$", "Workspace samples (the n of eqs 24-28)."),
    R("counts.azimuth", "-", "", "Azimuth values sampled."),
    R("counts.tilt", "-", "", "Tilt values sampled."),
    R("counts.torsion", "-", "", "Torsion values sampled."),
    R("psi1_deg[]", "deg", r"$\psi_1$", "The azimuths sampled."),
    R("psi2_deg[]", "deg", r"$\psi_2$", "The tilts sampled."),
    R("psi3_deg[]", "deg", r"$\psi_3$", "The torsions sampled."),
)
_DESIGN_SPACE = (
    R("f_min", "-", r"$f_{\min}$", "Least f_i = n_i . v_i over the continuous workspace "
      "(eq 16)."),
    R("f_max", "-", r"$f_{\max}$", "Largest f_i over the continuous workspace (eq 16)."),
    R("D1_deg", "deg", "$D_1$", "Half-width of |alpha1 - alpha2|: acos(-f_min) (eq 19)."),
    R("D2_deg", "deg", "$D_2$", "Half-width of |alpha1 + alpha2 - 180|: acos(f_max) (eq 19)."),
)  # fmt: skip
_MARGINS = R("margins_deg[]", "deg", "", "How far the design lies inside each inequality of "
             "eq 19 (negative: outside).")  # fmt: skip
_MINIMUM = (
    R("inverse_condition", "-", r"$\min\,1/\kappa$", "Least 1/kappa on the closed workspace, "
      "boundary included."),
    R("psi_deg[]", "deg", r"$\psi$", "Where: [psi1, psi2, psi3]."),
    R("grid_points", "-", "", "Points of the boundary-inclusive grid searched."),
)  # fmt: skip
_COMMON = (
    *prefixed("workspace", _WORKSPACE),
    *prefixed("sampling", _SAMPLING),
)


def _pose(prefix: str, optional: str = "") -> tuple[R, ...]:
    return (
        R(f"{prefix}.psi_deg[]", "deg", r"$\psi$", "The orientation [psi1, psi2, psi3].",
          optional=optional),
        R(f"{prefix}.joint_angles_deg[]", "deg", r"$\theta_i$", "The actuated joint angles.",
          optional=optional),
        R(f"{prefix}.inverse_condition", "-", _KAPPA, "1/kappa there (eqs 21-22).",
          optional=optional),
        R(f"{prefix}.det_a", "-", r"$\det A$", "det(A) there: 0 at a type-II singularity.",
          optional=optional),
    )  # fmt: skip


def _extremes(prefix: str, where: str) -> tuple[R, ...]:
    return (
        R(f"{prefix}.min_inverse_condition", "-", r"$\min\,1/\kappa$", f"Least 1/kappa {where}."),
        R(f"{prefix}.max_inverse_condition", "-", r"$\max\,1/\kappa$",
          f"Largest 1/kappa {where}."),
        R(f"{prefix}.unreachable_points", "-", "", f"Points {where} without inverse kinematics."),
    )  # fmt: skip


_GIVEN = "with given orientations"

CONDITIONING_MAP_RESULT_PATHS = (
    *prefixed("design", _ANGLES),
    _BRANCH,
    *_COMMON,
    *prefixed("indices", _INDICES),
    *prefixed("workspace_minimum", _MINIMUM),
    *prefixed("design_space", (*_DESIGN_SPACE, _MARGINS)),
    R("type_ii_singularity.min_abs_det_a", "-", r"$\min\,|\det A|$", "Least |det A| over the "
      "samples."),
    R("type_ii_singularity.min_det_a_squared", "-", r"$\min\,(\det A)^2$", "Its square, the "
      "left side of eq 30."),
    R("type_ii_singularity.at_psi_deg[]", "deg", r"$\psi$", "Where: [psi1, psi2, psi3]."),
    R("type_ii_singularity.det_a_range[]", "-", r"$\det A$", "[least, largest] det(A)."),
    R("inverse_kinematics.samples", "-", "$n$", "Workspace samples."),
    R("inverse_kinematics.real", "-", "", "Samples with real inverse kinematics."),
    R("inverse_kinematics.unreachable[]", "-", "", "Indices of the samples without.",
      optional=_UNREACHABLE),
    R("inverse_kinematics.unreachable_psi_deg[][]", "deg", r"$\psi$", "Those samples' "
      "orientations.", optional=_UNREACHABLE),
    *_pose("inverse_kinematics.entries[]"),
    *_pose("orientations[]", optional=_GIVEN),
    R("orientations[].condition_number", "-", r"$\kappa$", "kappa there (eqs 21-22).",
      optional=_GIVEN),
    R("maps.azimuth_deg.from", "deg", r"$\psi_1$", "The maps' first azimuth."),
    R("maps.azimuth_deg.to", "deg", r"$\psi_1$", "The maps' last azimuth."),
    R("maps.azimuth_deg.points", "-", "", "Azimuths per map."),
    R("maps.tilt_deg.from", "deg", r"$\psi_2$", "The maps' first tilt."),
    R("maps.tilt_deg.to", "deg", r"$\psi_2$", "The maps' last tilt."),
    R("maps.tilt_deg.points", "-", "", "Tilts per map."),
    R("maps.panels[].torsion_deg", "deg", r"$\psi_3$", "The map's torsion."),
    *_extremes("maps.panels[]", "on the map"),
    R("torsion_sweeps[].psi1_deg", "deg", r"$\psi_1$", "The sweep's azimuth."),
    R("torsion_sweeps[].psi2_deg", "deg", r"$\psi_2$", "The sweep's tilt."),
    R("torsion_sweeps[].psi3_deg.from", "deg", r"$\psi_3$", "The sweep's first torsion."),
    R("torsion_sweeps[].psi3_deg.to", "deg", r"$\psi_3$", "The sweep's last torsion."),
    R("torsion_sweeps[].psi3_deg.step", "deg", "", "The sweep's step."),
    R("torsion_sweeps[].min_at_psi3_deg", "deg", r"$\psi_3$", "Where the least 1/kappa is."),
    *_extremes("torsion_sweeps[]", "over the turn"),
)  # fmt: skip

_RECTANGLE = (
    R("abs_alpha_difference_max_deg", "deg", "$D_1$", "Largest |alpha1 - alpha2| (eq 19)."),
    R("abs_alpha_sum_minus_180_max_deg", "deg", "$D_2$",
      "Largest |alpha1 + alpha2 - 180| (eq 19)."),
    R("corners_deg[][]", "deg", "", "The rectangle's corners [alpha1, alpha2]."),
    R("alpha1_range_deg[]", "deg", r"$\alpha_1$", "The range of alpha1 it spans."),
    R("alpha2_range_deg[]", "deg", r"$\alpha_2$", "The range of alpha2 it spans."),
    R("area_deg2", "deg^2", "", "Its area in the alpha1-alpha2 plane, 2 D1 D2."),
)  # fmt: skip

DESIGN_SPACE_RESULT_PATHS = (
    *prefixed("workspace", _WORKSPACE),
    R("gamma_deg", "deg", r"$\gamma$", "The gamma used."),
    R("designs[].beta_deg", "deg", r"$\beta$", "The beta."),
    R("designs[].gamma_deg", "deg", r"$\gamma$", "The gamma."),
    *prefixed("designs[]", _DESIGN_SPACE),
    *prefixed("designs[].rectangle", _RECTANGLE),
    R("summary.betas", "-", "", "Betas evaluated."),
    R("summary.rectangles", "-", "", "Betas with a rectangle of designs."),
    R("summary.degenerate_betas_deg[]", "deg", r"$\beta$", "Betas whose design space is a "
      "line."),
    R("summary.empty_betas_deg[]", "deg", r"$\beta$", "Betas with no design.",
      optional="when some beta leaves no feasible design"),
    R("summary.widest_beta_deg", "deg", r"$\beta$", "The beta with the widest rectangle."),
    R("index_map.beta_deg", "deg", r"$\beta$", "The map's beta."),
    R("index_map.gamma_deg", "deg", r"$\gamma$", "The map's gamma."),
    R("index_map.branch", "-", "", "The branch sign (eq 29)."),
    R("index_map.points_per_side", "-", "", "Grid designs per side of the map."),
    R("index_map.min", "-", _MEAN_SQUARE, "Least mean(1/kappa^2) on the map (eq 28)."),
    R("index_map.max", "-", _MEAN_SQUARE, "Largest mean(1/kappa^2) on the map (eq 28)."),
    R("index_map.unscored_designs", "-", "", "Grid designs without a value."),
    *prefixed("index_map.best[]", _ANGLES),
    *prefixed("index_map.best[].indices", _INDICES),
    *prefixed("sampling", _SAMPLING),
)  # fmt: skip

_WHEN_HELD = "when {} is held"

OPTIMISATION_RESULT_PATHS = (
    *prefixed("optimum", (*_ANGLES, *_INDICES)),
    *prefixed("optimum.workspace_minimum", _MINIMUM),
    *prefixed("optimum.design_space", (*_DESIGN_SPACE, _MARGINS)),
    R("optimum.start", "-", "", "The start the optimum came from."),
    *prefixed("optimum.found_as", _ANGLES),
    *prefixed("optimum.twins[]", (*_ANGLES, _BRANCH)),
    R("optimum.twins[].shift_deg[]", "deg", "", "The shift [psi1, psi2, psi3] of the "
      "samples on which the twin reproduces every 1/kappa of the optimum."),
    *prefixed("optimum.twins[].indices", _INDICES),
    R("starts[].index", "-", "", "The start."),
    *prefixed("starts[].start", _ANGLES),
    *prefixed("starts[].end", _ANGLES),
    R("starts[].x0[]", "mixed", "", "The solver's start variables, named in 'variables': "
      "s, t, u pure numbers, beta and gamma in radians."),
    R("starts[].x[]", "mixed", "", "The solver's end variables, likewise."),
    R("starts[].status", "-", "", "The solver's status code."),
    R("starts[].nfev", "-", "", "Residual evaluations the solver counted."),
    R("starts[].evaluations", "-", "", "Residual evaluations spent, finite differences "
      "included."),
    R("starts[].mean_square_inverse_condition", "-", _MEAN_SQUARE, "The end design's eq 28."),
    *prefixed("starts[].indices", _INDICES),
    R("evaluations", "-", "", "Residual evaluations over all starts."),
    R("screening.candidates_per_start", "-", "", "Designs screened per start."),
    R("screening.candidates", "-", "", "Designs screened in all."),
    R("screening.evaluations", "-", "", "Designs scored by the screen."),
    R("budget.starts", "-", "", "Starts."),
    R("budget.max_evaluations_per_start", "-", "", "The evaluation budget of a start."),
    *(R(f"held_deg.{name}", "deg", symbol, f"The held {name}.", optional=_WHEN_HELD.format(name))
      for name, symbol in (("alpha1", r"$\alpha_1$"), ("alpha2", r"$\alpha_2$"))),
    R("held_deg.beta", "deg", r"$\beta$", "The held beta."),
    R("held_deg.gamma", "deg", r"$\gamma$", "The held gamma."),
    R("bounds_deg.beta_deg[]", "deg", r"$\beta$", "The search range of a free beta."),
    R("bounds_deg.gamma_deg[]", "deg", r"$\gamma$", "The search range of a free gamma.",
      optional="when gamma is free and not tied to beta"),
    _BRANCH,
    R("seed", "-", "", "The seed of the starts."),
    R("singularity_tolerance", "-", r"$\lambda$", "lambda of eq 30.",
      optional="when a singularity tolerance is given"),
    *_COMMON,
    R("paper.example", "-", "", "The paper's example (1-3)."),
    *prefixed("paper.designs[]", _ANGLES),
    R("paper.designs[].printed", "-", _MEAN_SQUARE, "The value the paper prints (its 'C_n', "
      "eq 28)."),
    *prefixed("paper.designs[].indices", _INDICES),
)  # fmt: skip
