"""The ``fourbar-grashof`` job: Grashof type, Barker's class and fully turning link pairs.

Grashof's criterion and Barker's classes come from :mod:`worker.families.chains.kinematics.fourbar`
(docs/methods/chains.md: in a Grashof chain the shortest link turns fully relative to
every other).  The plot shows the chain's range of motion with the ground fixed and which
links turn fully relative to which.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.figures import figure_artifacts
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.chains.fourbar_spec import FourBarGrashofSpec
from worker.families.chains.kinematics.fourbar import (
    FourBarClassification,
    classify_four_bar,
    four_bar_poses,
)
from worker.families.chains.plots import fourbar as plots

__all__ = ["POSE_SAMPLES", "fourbar_result", "run_fourbar_grashof"]

#: Input angles sampled over a full turn for the range-of-motion plot.
POSE_SAMPLES = 721


def fourbar_result(classified: FourBarClassification, length_unit: str) -> dict[str, Any]:
    """The result document of one classified four-bar."""
    check = classified.check
    pairs = [[i, j] for i in range(4) for j in range(i + 1, 4) if bool(classified.full_turns[i, j])]
    return {
        "lengths": list(classified.lengths),
        "ground": classified.ground,
        "grashof": classified.grashof,
        "classification": classified.classification,
        "barker": {
            "class": classified.barker.number,
            "code": classified.barker.code,
            "name": classified.barker.name,
        },
        "criterion": {
            "shortest": int(check.shortest),
            "longest": int(check.longest),
            "s_plus_l": check.s_plus_l,
            "p_plus_q": check.p_plus_q,
            "margin": check.p_plus_q - check.s_plus_l,
        },
        "links": [
            {
                "index": k,
                "length": classified.lengths[k],
                "role": classified.roles[k],
                "motion": classified.motion(k),
                "turns_fully_relative_to": [
                    j for j in range(4) if bool(classified.full_turns[k, j])
                ],
            }
            for k in range(4)
        ],
        "full_turns": pairs,
        "length_unit": length_unit,
    }


def _notes(classified: FourBarClassification) -> list[str]:
    check = classified.check
    s = int(check.shortest)
    if classified.grashof == "grashof":
        return [
            f"Grashof: s + l = {check.s_plus_l:g} < p + q = {check.p_plus_q:g}; the shortest "
            f"link {s} ({classified.roles[s]}) turns fully relative to every other link, and "
            "no other pair does."
        ]
    if classified.grashof == "non-grashof":
        return [
            f"Non-Grashof: s + l = {check.s_plus_l:g} > p + q = {check.p_plus_q:g}; no link "
            "turns fully relative to any other (every inversion is a triple rocker)."
        ]
    return [
        f"Change point: s + l = p + q = {check.p_plus_q:g}. All four links can fall into "
        "line; there the chain can switch assembly branch, and the fully turning pairs pass "
        "through that flat configuration (a real linkage needs help to pass it the right way)."
    ]


def run_fourbar_grashof(spec: FourBarGrashofSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    ctx.report_progress(0.0, "classification")
    classified = classify_four_bar(spec.lengths, spec.ground)
    result = fourbar_result(classified, spec.length_unit)
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        ctx.report_progress(50.0, "plots")
        artifacts = _artifacts(spec, classified)
    ctx.report_progress(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(_notes(classified)))


def _artifacts(spec: FourBarGrashofSpec, classified: FourBarClassification) -> tuple[Artifact, ...]:
    angles = np.linspace(0.0, 2.0 * np.pi, POSE_SAMPLES)
    figure = plots.fourbar_figure(
        four_bar_poses(spec.lengths, spec.ground, angles),
        lengths=classified.lengths,
        roles=classified.roles,
        full_turns=classified.full_turns,
        title=f"Four-bar ({', '.join(f'{v:g}' for v in classified.lengths)}): "
        f"{classified.classification}, Barker {classified.barker.number} "
        f"{classified.barker.code}",
        length_unit=spec.length_unit,
    )
    return figure_artifacts(figure, "fourbar_motion", "Range of motion and fully turning links")
