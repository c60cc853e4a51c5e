"""The paper's worked examples (Huang et al. 2004, §IV, Figs 4-9, Table I), ready to POST.

The numbers are the paper's, exactly as printed; what re-computation found wrong with
them is listed in docs/methods/planar-parallel.md and reported in the jobs' ``notes``
and ``paper_errata`` (:mod:`worker.families.planar_parallel.errata`).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from worker.processes import PaperPoint, ProcessExample

__all__ = [
    "CONDITIONING_MAP_EXAMPLES",
    "FIG_4_DELTAS",
    "FIG_4_LIMIT",
    "OPTIMISATION_EXAMPLES",
    "OPTIMISATION_PAPER_POINTS",
    "PAPER_ASPECT_RATIO",
    "TABLE_I",
    "TableIColumn",
]

#: Fig. 4-5: the isotropic designs delta = 1.5, 2.0, 2.5, W_kappa0 bounded by 1/kappa0 = 0.5.
FIG_4_DELTAS = (1.5, 2.0, 2.5)
FIG_4_LIMIT = 0.5
#: lambda = b/h of both Table I columns.
PAPER_ASPECT_RATIO = 4.0


@dataclass(frozen=True)
class TableIColumn:
    """One column of the paper's Table I, as printed (l1 = 1)."""

    allowable_pressure_angle_deg: float
    inverse_condition_limit: float
    delta: float
    e: float
    h: float
    H_prime: float
    mean_inverse_condition: float
    S: float
    eta: float

    @property
    def b(self) -> float:
        """b = lambda h (the paper prints h only)."""
        return PAPER_ASPECT_RATIO * self.h


#: Table I: ([beta] = 30°, 1/kappa0 = 0.526) and ([beta] = 35°, 1/kappa0 = 0.581).
TABLE_I = (
    TableIColumn(30.0, 0.526, 1.7, 0.4950, 0.7322, 1.3056, 0.7444, 2.0354, 0.7453),
    TableIColumn(35.0, 0.581, 1.85, 0.6001, 0.6667, 1.5178, 0.8004, 1.7778, 0.8004),
)


def _corners(column: TableIColumn) -> list[list[float]]:
    """The four corners of the paper's printed rectangle W_lambda."""
    half_b, half_h = column.b / 2, column.h / 2
    top, bottom = -column.H_prime + half_h, -column.H_prime - half_h
    return [
        [round(v, 4) for v in corner]
        for corner in ((-half_b, top), (half_b, top), (half_b, bottom), (-half_b, bottom))
    ]


CONDITIONING_MAP_EXAMPLES = (
    *(
        ProcessExample(
            title=f"Figs 4-5({'abc'[i]}): the isotropic design delta = {delta:g}, "
            f"W_kappa0 at 1/kappa0 = {FIG_4_LIMIT:g}",
            inputs=MappingProxyType(
                {
                    "l2": delta,
                    "architecture": "isotropic",
                    "inverse_condition_limit": FIG_4_LIMIT,
                    "grid": {"points_per_axis": 301},
                }
            ),
            description="The proximal-arm robot of eq (12) (l1 = 1, e = (√2/2)(delta - 1)) in "
            "the paper's working mode [1, -1]: 1/kappa and beta_min over the reachable "
            "workspace with W_kappa0 outlined; isotropic (1/kappa = 1) at (0, -H).",
        )
        for i, delta in enumerate(FIG_4_DELTAS)
    ),
    *(
        ProcessExample(
            title=f"Table I, [beta] = {column.allowable_pressure_angle_deg:g}°: the design "
            f"delta = {column.delta:g} and the corners of the paper's rectangle",
            inputs=MappingProxyType(
                {
                    "l2": column.delta,
                    "architecture": "isotropic",
                    "inverse_condition_limit": column.inverse_condition_limit,
                    "points": _corners(column),
                    "grid": {"points_per_axis": 301},
                }
            ),
            description=f"1/kappa and the pressure angles at the corners of the printed "
            f"W_lambda (b = 4h, h = {column.h:g}, H' = {column.H_prime:g}); the "
            f"paper's rectangle should lie in W_kappa0 (1/kappa >= "
            f"{column.inverse_condition_limit:g}).",
        )
        for column in TABLE_I
    ),
    ProcessExample(
        title="Telescopic-leg type (Fig. 1b), e = 0.5",
        inputs=MappingProxyType(
            {
                "actuation": "telescopic-leg",
                "l2": 1.0,
                "e": 0.5,
                "inverse_condition_limit": 0.5,
                "grid": {"points_per_axis": 301},
            }
        ),
        description="Legs from (±0.5, 0) actuated by their length (A = E2): 1/kappa depends "
        "only on the angle between the legs and is 1 on the circle x² + y² = e².",
    ),
)

OPTIMISATION_EXAMPLES = (
    *(
        ProcessExample(
            title=f"Table I, [beta] = {column.allowable_pressure_angle_deg:g}°, lambda = 4: "
            "the paper's design from its inputs",
            inputs=MappingProxyType(
                {
                    "allowable_pressure_angle_deg": column.allowable_pressure_angle_deg,
                    "aspect_ratio": PAPER_ASPECT_RATIO,
                }
            ),
            description="1/kappa0 from eq (17), maximised over delta in [1, 2.5]; the sweep "
            "of S/S_max, mean 1/kappa and eta over delta (step 0.01, Fig. 8), the optimum "
            "and the window where eta is within 0.001 of its maximum.",
        )
        for column in TABLE_I
    ),
    *(
        ProcessExample(
            title=f"Table I, 1/kappa0 = {column.inverse_condition_limit:g} at delta = "
            f"{column.delta:g}: the paper's printed row",
            inputs=MappingProxyType(
                {
                    "inverse_condition_limit": column.inverse_condition_limit,
                    "delta": column.delta,
                    "aspect_ratio": PAPER_ASPECT_RATIO,
                }
            ),
            description="One design at the paper's printed limit and delta: e, h, H', S, "
            "the mean 1/kappa over W_lambda and eta (S_max over delta in [1, 2.5]).",
        )
        for column in TABLE_I
    ),
)


#: Table I's optima (delta at each printed 1/kappa0, lambda = 4), which a design study
#: of planar2dof-optimisation over delta marks.
OPTIMISATION_PAPER_POINTS = tuple(
    PaperPoint(
        label=f"Table I, [β] = {c.allowable_pressure_angle_deg:g}°: δ = {c.delta:g}",
        inputs={
            "delta": c.delta,
            "inverse_condition_limit": c.inverse_condition_limit,
            "aspect_ratio": PAPER_ASPECT_RATIO,
        },
    )
    for c in TABLE_I
)
