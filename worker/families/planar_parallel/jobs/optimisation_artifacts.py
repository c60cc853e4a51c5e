"""The optimisation's files: the paper's Figs 6-9 as PNG/SVG and the data as CSV/NPZ.

* ``conditioning_limit``: 1/kappa0 against [beta] and delta (Fig. 7);
* ``design_indices``: S/S_max, mean 1/kappa and eta against delta (Fig. 8; sweeps only);
* ``normalised_rectangle``: 1/kappa and beta_min over W_lambda (Fig. 9);
* ``rectangle_workspace``: W_lambda inside W_kappa0 over the 1/kappa map (Fig. 6);
* ``sweep.csv``: one row per delta; ``optimisation.npz``: the sweep and every figure's
  arrays.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import (
    DIMENSIONLESS,
    column,
    columns_csv,
    job_metadata,
    npz_artifact,
)
from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.discretisation import FIG9_MESH, MAP_POINTS_PER_AXIS
from worker.families.planar_parallel.jobs.architecture import default_bounds
from worker.families.planar_parallel.jobs.design_rows import sweep_entry
from worker.families.planar_parallel.plots import design as plots
from worker.families.planar_parallel.specs import DEFAULT_DELTA_RANGE, OptimisationSpec

if TYPE_CHECKING:
    from worker.families.planar_parallel.jobs.optimisation import SweepOutcome

__all__ = ["CSV_NAME", "FIG7_ANGLES_DEG", "NPZ_NAME", "optimisation_artifacts"]

CSV_NAME, NPZ_NAME = "sweep.csv", "optimisation.npz"
#: The allowable pressure angles drawn in Fig. 7 (the request's is added).
FIG7_ANGLES_DEG = (20.0, 25.0, 30.0, 35.0, 40.0, 45.0)
FIG7_SAMPLES = 301
FloatArray = NDArray[np.float64]
#: The paper's working mode, the optimum design's (eq 12).
PAPER_MODE = (1, -1)


def optimisation_artifacts(
    spec: OptimisationSpec,
    limit: float,
    limit_delta: float | None,
    outcome: SweepOutcome,
    progress: ProgressReporter,
) -> tuple[Artifact, ...]:
    """Plots (unless ``spec.plots`` is false) then the CSV and NPZ. The chosen design
    is checked once, as a Robot in the paper's working mode, and passed on."""
    robot = None
    if outcome.design is not None:
        robot = pp.Robot(pp.isotropic_architecture(outcome.design.row.delta), PAPER_MODE)
    arrays = _figure_arrays(spec, limit, outcome, robot)
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        artifacts = _plots(spec, limit, limit_delta, outcome, arrays, progress, robot)
    progress.report(96.0, "data files")
    return (*artifacts, *_data(spec, outcome, arrays, limit))


def _figure_arrays(
    spec: OptimisationSpec, limit: float, outcome: SweepOutcome, robot: pp.Robot | None
) -> dict[str, FloatArray]:
    """Fig. 7 curves, and Figs 6 and 9 of the chosen design when there is one."""
    span = spec.sweep_range if spec.delta is None else DEFAULT_DELTA_RANGE
    angles = sorted({*FIG7_ANGLES_DEG, *([spec.allowable_pressure_angle_deg] if
                                         spec.allowable_pressure_angle_deg else [])})  # fmt: skip
    deltas = np.linspace(span[0], span[1], FIG7_SAMPLES)
    arrays: dict[str, FloatArray] = {
        "fig7_deltas": deltas,
        "fig7_allowable_angles_deg": np.asarray(angles),
        "fig7_limits": np.stack(
            [pp.condition_limit_from_pressure_angle(a, deltas) for a in angles]
        ),
    }
    if outcome.design is None or robot is None:
        return arrays
    rect = outcome.design.row.rectangle
    xs = np.linspace(-rect.b / 2, rect.b / 2, FIG9_MESH)
    ys = np.linspace(-rect.H_prime - rect.h / 2, -rect.H_prime + rect.h / 2, FIG9_MESH)
    inside = pp.robot_map(robot, xs, ys)
    x0, x1, y0, y1 = default_bounds(robot.arch)
    mx = np.linspace(x0, x1, MAP_POINTS_PER_AXIS)
    my = np.linspace(y0, y1, MAP_POINTS_PER_AXIS)
    arrays |= {
        "rectangle_x": xs,
        "rectangle_y": ys,
        "rectangle_inverse_condition": inside.inverse_condition,
        "rectangle_min_pressure_angle_deg": np.degrees(inside.min_pressure_angle),
        "map_x": mx,
        "map_y": my,
        "map_inverse_condition": pp.robot_map(robot, mx, my).inverse_condition,
    }
    return arrays


def _design_text(row: pp.SweepRow) -> str:
    rect = row.rectangle
    return (
        rf"$\delta$ = {row.delta:.4g}, $e$ = {row.e:.4f}: $b$ = {rect.b:.4f}, "
        rf"$h$ = {rect.h:.4f}, $H'$ = {rect.H_prime:.4f}, $S$ = {rect.S:.4f} ($l_1$ = 1)"
    )


def _plots(
    spec: OptimisationSpec,
    limit: float,
    limit_delta: float | None,
    outcome: SweepOutcome,
    arrays: dict[str, FloatArray],
    progress: ProgressReporter,
    robot: pp.Robot | None,
) -> tuple[Artifact, ...]:
    """Figs 7 and 8 (a sweep only), then the design's Figs 9 and 6 (progress 84-96 %)."""
    progress.report(84.0, "plot of 1/kappa0 against [beta] and delta (Fig. 7)")
    angle = spec.allowable_pressure_angle_deg
    fig7 = plots.conditioning_limit_figure(
        arrays["fig7_deltas"], arrays["fig7_allowable_angles_deg"], arrays["fig7_limits"],
        chosen_angle_deg=angle, chosen_limit=limit, chosen_delta=limit_delta,
        title=r"Conditioning limit $1/\kappa_0$ from the allowable pressure angle $[\beta]$ "
        "(Fig. 7)",
    )  # fmt: skip
    artifacts = list(figure_artifacts(fig7, "conditioning_limit",
                                      "1/kappa0 against [beta] and delta (Fig. 7)"))  # fmt: skip
    setting = rf"$1/\kappa_0$ = {limit:.5g}, $\lambda$ = {spec.aspect_ratio:g}"
    if spec.delta is None and len(outcome.rows) > 1:
        progress.report(87.0, "plot of the indices against delta (Fig. 8)")
        columns = _sweep_columns(outcome)
        optimum = None if outcome.design is None else outcome.design.row.delta
        fig8 = plots.design_indices_figure(
            columns["delta"], columns["S_over_S_max"], columns["mean_inverse_condition"],
            columns["eta"], optimum_delta=optimum, window=outcome.window,
            title=r"Performance indices against $\delta$ (Fig. 8)",
            subtitle=rf"{setting}, mean $1/\kappa$ on {spec.mean_mesh} × {spec.mean_mesh} nodes",
        )  # fmt: skip
        artifacts += figure_artifacts(
            fig8, "design_indices", "S/S_max, mean 1/kappa and eta against delta (Fig. 8)"
        )
    if outcome.design is not None and robot is not None:
        artifacts += _design_plots(spec, limit, outcome.design.row, robot, arrays, setting,
                                   progress)  # fmt: skip
    return tuple(artifacts)


def _design_plots(
    spec: OptimisationSpec, limit: float, row: pp.SweepRow, robot: pp.Robot,
    arrays: dict[str, FloatArray], setting: str, progress: ProgressReporter,
) -> tuple[Artifact, ...]:  # fmt: skip
    progress.report(90.0, "plot of the rectangle (Fig. 9)")
    rect = row.rectangle
    fig9 = plots.normalised_rectangle_figure(
        arrays["rectangle_x"] / rect.b, (arrays["rectangle_y"] + rect.H_prime) / rect.b,
        arrays["rectangle_inverse_condition"], arrays["rectangle_min_pressure_angle_deg"],
        inverse_condition_limit=limit, allowable_angle_deg=spec.allowable_pressure_angle_deg,
        title=r"$1/\kappa$ and $\beta_{\min}$ over the rectangle $W_\lambda$ (Fig. 9)",
        subtitle=_design_text(row),
    )  # fmt: skip
    fig9_files = figure_artifacts(
        fig9, "normalised_rectangle", "1/kappa and beta_min over the normalised rectangle (Fig. 9)"
    )
    progress.report(93.0, "plot of the rectangle in W_kappa0 (Fig. 6)")
    e = row.e
    workspace = plots.rectangle_workspace_figure(
        arrays["map_x"], arrays["map_y"], arrays["map_inverse_condition"],
        inverse_condition_limit=limit, rectangle=(rect.b, rect.h, rect.H_prime),
        joints=[[e, 0.0], [-e, 0.0]], isotropic_point=pp.robot_isotropic_point(robot),
        title=rf"The rectangle $W_\lambda$ inside $W_{{\kappa 0}}$ (Fig. 6), {setting}",
        subtitle=_design_text(row),
    )  # fmt: skip
    return (
        *fig9_files,
        *figure_artifacts(workspace, "rectangle_workspace",
                          "The rectangle W_lambda inside W_kappa0 (Fig. 6)"),
    )  # fmt: skip


#: The sweep's quantities and their units; lengths are normalised, l1 = 1 (the unit
#: "l1" in every file and figure of this process).
NORMALISED = "l1"
_SWEEP_COLUMNS = {
    "delta": DIMENSIONLESS, "e": NORMALISED, "h": NORMALISED, "b": NORMALISED,
    "H_prime": NORMALISED, "S": f"{NORMALISED}^2", "S_over_S_max": DIMENSIONLESS,
    "mean_inverse_condition": DIMENSIONLESS, "eta": DIMENSIONLESS,
    "min_pressure_angle_deg": "deg", "found": DIMENSIONLESS,
}  # fmt: skip


def _sweep_columns(outcome: SweepOutcome) -> dict[str, NDArray[Any]]:
    entries = [sweep_entry(row) for row in outcome.rows]
    columns: dict[str, NDArray[Any]] = {}
    for name in _SWEEP_COLUMNS:
        values = [entry[name] for entry in entries]
        columns[name] = (np.asarray(values, dtype=bool) if name == "found"
                         else np.asarray([np.nan if v is None else v for v in values],
                                         dtype=float))  # fmt: skip
    return columns


def _data(
    spec: OptimisationSpec, outcome: SweepOutcome, arrays: dict[str, FloatArray], limit: float
) -> tuple[Artifact, Artifact]:
    columns = _sweep_columns(outcome)
    named = {
        column(name.removesuffix("_deg"), _SWEEP_COLUMNS[name]): values
        for name, values in columns.items()
    }
    csv = columns_csv(CSV_NAME, named, "The delta sweep, one row per delta (CSV)")
    units = {f"sweep_{name}": unit for name, unit in _SWEEP_COLUMNS.items()}
    units |= {
        "fig7_deltas": DIMENSIONLESS, "fig7_allowable_angles_deg": "deg",
        "fig7_limits": DIMENSIONLESS, "rectangle_x": NORMALISED, "rectangle_y": NORMALISED,
        "rectangle_inverse_condition": DIMENSIONLESS,
        "rectangle_min_pressure_angle_deg": "deg", "map_x": NORMALISED, "map_y": NORMALISED,
        "map_inverse_condition": DIMENSIONLESS, "inverse_condition_limit": DIMENSIONLESS,
        "S_max": f"{NORMALISED}^2",
    }  # fmt: skip
    axes: dict[str, tuple[str, ...]] = {
        f"sweep_{name}": ("sweep_delta",) for name in _SWEEP_COLUMNS if name != "delta"
    }
    axes |= {"fig7_limits": ("fig7_allowable_angles_deg", "fig7_deltas")}
    if "rectangle_x" in arrays:
        axes |= {
            "rectangle_inverse_condition": ("rectangle_y", "rectangle_x"),
            "rectangle_min_pressure_angle_deg": ("rectangle_y", "rectangle_x"),
            "map_inverse_condition": ("map_y", "map_x"),
        }
    everything = {
        **{f"sweep_{name}": values for name, values in columns.items()},
        **arrays,
        "inverse_condition_limit": np.array(limit),
        "S_max": np.array(outcome.S_max),
    }
    npz = npz_artifact(
        NPZ_NAME,
        everything,
        "The sweep and the figures' arrays (NumPy)",
        units={name: units[name] for name in everything},
        axes=axes,
        metadata=job_metadata("planar2dof-optimisation", spec.model_dump(mode="json")),
    )
    return csv, npz
