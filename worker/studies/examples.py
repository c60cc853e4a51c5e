"""The worked examples of ``design-study``, each a study of one family's process; the
first (Bai's Example I on a 10° grid) lends its fixed inputs to the 10^6-design test
and the benchmarks."""

from __future__ import annotations

from types import MappingProxyType

from worker.processes import ProcessExample

__all__ = ["STUDY_EXAMPLES"]

_LIMITS = [[-150, 150], [-150, 150], [-175, 175]]
STUDY_EXAMPLES = (
    ProcessExample(
        title="SPM: C_n over (alpha1, alpha2) at beta = 90 deg, Table 1's optimum marked",
        inputs=MappingProxyType(
            {
                "process": "spm-conditioning-map",
                "fixed": {
                    "beta_deg": 90,
                    "gamma_deg": 0,
                    "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360]},
                },
                "vary": {"alpha1_deg": [30, 150, 13], "alpha2_deg": [30, 150, 13]},
                "objectives": {
                    "indices.rms_inverse_condition": "max",
                    "indices.min_inverse_condition": "max",
                },
            }
        ),
        description="Bai's Example I (a 120 deg cone, a full turn, beta = 90 deg): C_n (eq 25) "
        "and the worst 1/kappa of 169 designs on a 10 deg grid, as heat maps with Table 1's "
        "optimum (60, 90) and its twin (120, 90) marked. The two are the study's best, C_n "
        "0.5453 (the paper prints its square, 0.28 for 0.2974); grey designs leave some of "
        "the cone unreachable or singular.",
    ),
    ProcessExample(
        title="Five-bar: eta over delta through planar2dof-optimisation, Table I's delta marked",
        inputs=MappingProxyType(
            {
                "process": "planar2dof-optimisation",
                "fixed": {"inverse_condition_limit": 0.526, "aspect_ratio": 4},
                "vary": {"delta": [1.5, 1.9, 5]},
                "objectives": {"optimum.eta": "max", "optimum.S": "max"},
            }
        ),
        description="Huang et al.'s proximal-arm five-bar at 1/kappa0 = 0.526 and lambda = 4: "
        "the global index eta and the rectangle's area S at five deltas around Table I's "
        "delta = 1.7 (marked), each the optimisation process's own numbers.",
    ),
    ProcessExample(
        title="Chains: Fig 2d's place among the Fig 2 quadrangles as one link's length varies",
        inputs=MappingProxyType(
            {
                "process": "chain-parallelism",
                "fixed": {
                    "chains": [
                        {"name": "Fig 2a", "lengths": [15, 15, 15, 15]},
                        {"name": "Fig 2b", "lengths": [20, 10, 20, 10]},
                        {"name": "Fig 2c", "lengths": [20, 20, 10, 10]},
                        {"name": "Fig 2d", "lengths": [18, 15, 10, 17]},
                        {"name": "Fig 2e", "lengths": [18, 10, 17, 15]},
                    ],
                    "length_unit": "cm",
                },
                "vary": {"chains[3].lengths[2]": [6, 24, 19]},
                "objectives": {"chains[3].rank.by_Q": "min", "chains[3].Q_normalized": "min"},
            }
        ),
        description="The five quadrangles of the paper's Fig 2 with Fig 2d's third link from "
        "6 to 24 cm: where Fig 2d ranks by Q among them, and its normalised Q.",
    ),
    ProcessExample(
        title="3R arm: worst task-point d_z and total length over (l1, l2)",
        inputs=MappingProxyType(
            {
                "process": "planar3r-dexterity-map",
                "fixed": {
                    "links": [15, 14, 8],
                    "joint_limits_deg": _LIMITS,
                    "task_points": [[14, 14], [12, 8], [10, -3], [9, -7], [8, -8]],
                    "grid": {"points_per_axis": 5},
                },
                "vary": {"links[0]": [10, 20, 6], "links[1]": [8, 18, 6]},
                "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
            }
        ),
        description="Patel & Sobh's Example 1 under its joint limits, l3 = 8: 36 designs, "
        "the worst d_z at A..E against the arm's total length, and their Pareto front.",
    ),
    ProcessExample(
        title="SPM: RMS and worst 1/kappa over (alpha1, alpha2), a Sobol sample",
        inputs=MappingProxyType(
            {
                "process": "spm-conditioning-map",
                "fixed": {
                    "beta_deg": 90,
                    "gamma_deg": 0,
                    "workspace": {
                        "tilt_max_deg": 60,
                        "torsion_deg": [0, 360],
                        "samples": {"azimuth": 6, "tilt": 3, "torsion": 3},
                    },
                },
                "sample": {
                    "method": "sobol",
                    "count": 12,
                    "seed": 1,
                    "bounds": {"alpha1_deg": [45, 90], "alpha2_deg": [60, 120]},
                },
                "objectives": {
                    "indices.rms_inverse_condition": "max",
                    "indices.min_inverse_condition": "max",
                },
            }
        ),
        description="Bai's spherical manipulator with beta = 90 deg over a 60 deg tilt "
        "workspace: 12 Sobol designs of (alpha1, alpha2), the RMS and the worst 1/kappa.",
    ),
)
