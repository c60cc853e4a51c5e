"""The paper's worked examples (Bai 2010 §6, Figs 5-7, Tables 1-3), ready to POST.

The designs and printed values are the paper's, exactly as printed; what re-computation
found about them is in docs/methods/spherical-parallel.md and in the jobs' ``notes``
and ``paper_errata`` (:mod:`worker.families.spherical_parallel.errata`). The paper says only
"4 x 12 x 3 = 144" samples; every example uses the default reading of that page
("Sampling the workspace").
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from worker.processes import PaperPoint, ProcessExample

__all__ = [
    "CONDITIONING_MAP_EXAMPLES",
    "CONDITIONING_MAP_PAPER_POINTS",
    "DESIGN_SPACE_EXAMPLES",
    "EXAMPLE_1_WORKSPACE",
    "EXAMPLE_2_WORKSPACE",
    "EXAMPLE_3_WORKSPACE",
    "FIG_5_BETAS_DEG",
    "FIG_5_F_MAX",
    "FIG_5_F_MIN",
    "OPTIMISATION_EXAMPLES",
    "TABLE_1",
    "TABLE_2_GRAPHIC",
    "TABLE_2_NUMERICAL",
    "TABLE_3",
    "TABLE_3_PRINTED_TWIN",
    "PaperDesign",
]


@dataclass(frozen=True)
class PaperDesign:
    """A design of the paper's tables and the value it prints beside it ("C_n" or
    1/kappa; docs/methods/spherical-parallel.md: it is mean(1/kappa^2), eq 28)."""

    label: str
    alpha1_deg: float
    alpha2_deg: float
    beta_deg: float
    gamma_deg: float
    printed: float

    def angles(self) -> tuple[float, float, float, float]:
        return (self.alpha1_deg, self.alpha2_deg, self.beta_deg, self.gamma_deg)

    def inputs(self) -> dict[str, float]:
        return {"alpha1_deg": self.alpha1_deg, "alpha2_deg": self.alpha2_deg,
                "beta_deg": self.beta_deg, "gamma_deg": self.gamma_deg}  # fmt: skip


#: Example I: the active ball joint (gamma = 0), a 120° cone with a full turn.
EXAMPLE_1_WORKSPACE: dict[str, Any] = {"tilt_max_deg": 60.0, "torsion_deg": [0.0, 360.0]}
#: Example II: the Asada-Granito wrist, a 90° cone with a full turn.
EXAMPLE_2_WORKSPACE: dict[str, Any] = {"tilt_max_deg": 45.0, "torsion_deg": [0.0, 360.0]}
#: Example III: identical platforms, a 90° cone with 30° of torsion (read as [-15, 15]).
EXAMPLE_3_WORKSPACE: dict[str, Any] = {"tilt_max_deg": 45.0, "torsion_deg": [-15.0, 15.0]}

TABLE_1 = PaperDesign("Table 1", 60.0, 90.0, 90.0, 0.0, 0.28)
#: Table 1's supplementary optimum, printed in parenthesis: alpha1 = 120.
TABLE_1_TWIN_ALPHA1_DEG = 120.0
TABLE_2_NUMERICAL = PaperDesign("Table 2, numerical method", 48.0, 90.0, 90.0, 0.0, 0.72)
TABLE_2_GRAPHIC = PaperDesign("Table 2, graphic method (Asada-Granito)", 50.0, 105.0, 75.0,
                              0.0, 0.67)  # fmt: skip
TABLE_3 = PaperDesign("Table 3", 54.9, 115.4, 33.3, 33.3, 0.585)
#: Table 3's twin as printed in parenthesis: (alpha1, alpha2) = (115.4, 54.9).
TABLE_3_PRINTED_TWIN = (115.4, 54.9)

#: Fig. 5: sub-design spaces of Example I for these betas; for beta = 75 the paper gives
#: f_min = -0.707 and f_max = 0.966 (|a1 - a2| <= 45°, |a1 + a2 - 180°| <= 15°).
FIG_5_BETAS_DEG = (60.0, 75.0, 90.0)
FIG_5_F_MIN = -0.707
FIG_5_F_MAX = 0.966


def _map_example(design: PaperDesign, workspace: dict[str, Any], text: str) -> ProcessExample:
    return ProcessExample(
        title=f"{design.label}: ({design.alpha1_deg:g}, {design.alpha2_deg:g}, "
        f"{design.beta_deg:g}, gamma {design.gamma_deg:g})",
        inputs=MappingProxyType({**design.inputs(), "workspace": workspace}),
        description=text,
    )


CONDITIONING_MAP_EXAMPLES = (
    _map_example(
        TABLE_1,
        EXAMPLE_1_WORKSPACE,
        "Example I's optimum over a 120° cone with a "
        "full turn: mean(1/kappa^2) 0.2974 on the default 144 samples (printed 0.28); "
        "1/kappa reaches 0 on the workspace boundary.",
    ),
    _map_example(
        TABLE_2_NUMERICAL,
        EXAMPLE_2_WORKSPACE,
        "Example II's numerical design "
        "over a 90° cone: the default sweeps are the paper's Fig. 7 (psi1 = 35°, "
        "psi2 = 15, 30, 45).",
    ),
    _map_example(
        TABLE_2_GRAPHIC,
        EXAMPLE_2_WORKSPACE,
        "The Asada-Granito graphic design "
        "compared in Table 2 and Fig. 7 (printed 0.67; 0.616 on the default samples).",
    ),
    _map_example(
        TABLE_3,
        EXAMPLE_3_WORKSPACE,
        "Example III's printed optimum, identical "
        "platforms, 90° cone with torsion [-15, 15] (printed 0.585).",
    ),
)

DESIGN_SPACE_EXAMPLES = (
    ProcessExample(
        title="Figs 5-6: the active ball joint in a 120° cone, beta = 60, 75, 90",
        inputs=MappingProxyType(
            {
                "workspace": EXAMPLE_1_WORKSPACE,
                "gamma_deg": 0.0,
                "beta_deg": list(FIG_5_BETAS_DEG),
                "index_map": {"beta_deg": 75.0},
            }
        ),
        description="beta = 75: f_min = -0.707, f_max = 0.966, |a1 - a2| <= 45°, "
        "|a1 + a2 - 180°| <= 15°; beta = 60 degenerates to the line a1 + a2 = 180°. The "
        "index map is the paper's Fig. 6, its two optima at (60, 105) and (120, 75).",
    ),
    ProcessExample(
        title="Example III's design space: identical platforms, beta from 20 to 70",
        inputs=MappingProxyType(
            {
                "workspace": EXAMPLE_3_WORKSPACE,
                "identical_platforms": True,
                "beta_deg": {"start": 20.0, "stop": 70.0, "step": 5.0},
            }
        ),
        description="gamma = beta, a 90° cone with 30° of torsion: f over the continuous "
        "workspace by a grid search polished by projected Newton steps.",
    ),
)

OPTIMISATION_EXAMPLES = (
    ProcessExample(
        title="Table 1: the active ball joint in a 120° cone, full turn",
        inputs=MappingProxyType({"workspace": EXAMPLE_1_WORKSPACE, "gamma_deg": 0.0}),
        description="alpha1, alpha2, beta free, 8 starts: (60 or 120, 90, 90), "
        "mean(1/kappa^2) 0.2974 (printed as C_n = 0.28).",
    ),
    ProcessExample(
        title="Table 2: the Asada-Granito wrist, 90° cone, full turn",
        inputs=MappingProxyType({"workspace": EXAMPLE_2_WORKSPACE, "gamma_deg": 0.0}),
        description="The optimum is alpha1 ≈ 45.2 (or 134.8), alpha2 = beta = 90, "
        "mean(1/kappa^2) 0.7255: it beats the printed (48, 90, 90), 0.72 (0.7021 here).",
    ),
    ProcessExample(
        title="Table 3: identical platforms, 90° cone, 30° torsion",
        inputs=MappingProxyType({"workspace": EXAMPLE_3_WORKSPACE, "identical_platforms": True}),
        description="beta = gamma free: about (56.5, 87.3, 47.4), mean(1/kappa^2) 0.768 on "
        "the default samples, well above the printed (54.9, 115.4, 33.3), 0.585.",
    ),
    ProcessExample(
        title="Table 3 with beta = gamma held at the printed 33.3",
        inputs=MappingProxyType(
            {
                "workspace": EXAMPLE_3_WORKSPACE,
                "identical_platforms": True,
                "free": ["alpha1", "alpha2"],
                "beta_deg": 33.3,
            }
        ),
        description="Only the link angles free: about (58.1, 113.4) or (121.9, 66.6), "
        "mean(1/kappa^2) 0.582, next to the printed design's 0.579.",
    ),
)


def _paper_point(design: PaperDesign, workspace: dict[str, Any], what: str) -> PaperPoint:
    conditions = {"workspace.tilt_max_deg": workspace["tilt_max_deg"],
                  "workspace.torsion_deg": workspace["torsion_deg"]}  # fmt: skip
    return PaperPoint(
        label=f"{design.label} {what} ({design.alpha1_deg:g}°, {design.alpha2_deg:g}°)",
        inputs={**design.inputs(), **conditions},
    )


#: The designs of Tables 1-3 over their examples' workspaces (Table 1's optimum also as
#: its printed twin, alpha1 = 120), which a design study of spm-conditioning-map marks.
CONDITIONING_MAP_PAPER_POINTS = (
    _paper_point(TABLE_1, EXAMPLE_1_WORKSPACE, "optimum"),
    _paper_point(
        PaperDesign("Table 1", TABLE_1_TWIN_ALPHA1_DEG, 90.0, 90.0, 0.0, TABLE_1.printed),
        EXAMPLE_1_WORKSPACE,
        "optimum's twin",
    ),
    _paper_point(TABLE_2_NUMERICAL, EXAMPLE_2_WORKSPACE, "design"),
    _paper_point(TABLE_2_GRAPHIC, EXAMPLE_2_WORKSPACE, "design"),
    _paper_point(TABLE_3, EXAMPLE_3_WORKSPACE, "optimum"),
)
