"""The fourbar-grashof job: the paper's quadrangles and Patel & Sobh's virtual four-bar."""

from __future__ import annotations

import json
from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.contract import JobOutcome
from worker.families.chains import FOURBAR_GRASHOF
from worker.families.chains.examples import FOURBAR_GRASHOF_EXAMPLES
from worker.families.chains.fourbar_spec import FourBarGrashofSpec
from worker.families.chains.jobs import fourbar

RESULT_KEYS = {
    "lengths", "ground", "grashof", "classification", "barker", "criterion", "links",
    "full_turns", "length_unit",
}  # fmt: skip


@pytest.fixture(autouse=True)
def fast_fourbar_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(fourbar, "figure_artifacts", unrendered_artifacts)


def run(**inputs: Any) -> JobOutcome:
    return FOURBAR_GRASHOF.run(FourBarGrashofSpec.model_validate(inputs), RecordingContext())


def test_fig_3_is_a_triple_rocker() -> None:
    outcome = run(**FOURBAR_GRASHOF_EXAMPLES[0].inputs)
    result = json.loads(json.dumps(outcome.result))
    assert set(result) == RESULT_KEYS
    assert result["grashof"] == "non-grashof"
    assert result["classification"] == "triple-rocker"
    assert result["barker"] == {
        "class": "II-1", "code": "RRR1", "name": "non-Grashof triple-rocker, longest link grounded",
    }  # fmt: skip
    assert result["criterion"] == {"shortest": 1, "longest": 0, "s_plus_l": 47.0,
                                   "p_plus_q": 43.0, "margin": -4.0}  # fmt: skip
    assert result["full_turns"] == []
    assert [link["motion"] for link in result["links"]] == ["ground", "rocker", "rocker",
                                                             "rocker"]  # fmt: skip
    assert outcome.notes[0].startswith("Non-Grashof: s + l = 47 > p + q = 43")
    assert [a.name for a in outcome.artifacts] == ["fourbar_motion.png", "fourbar_motion.svg"]


def test_fig_2e_is_a_crank_rocker() -> None:
    result = run(**FOURBAR_GRASHOF_EXAMPLES[1].inputs).result
    assert (result["grashof"], result["classification"]) == ("grashof", "crank-rocker")
    assert result["barker"]["code"] == "GCRR"
    assert result["full_turns"] == [[0, 1], [1, 2], [1, 3]]
    assert result["links"][1] == {
        "index": 1, "length": 10.0, "role": "input", "motion": "crank",
        "turns_fully_relative_to": [0, 2, 3],
    }  # fmt: skip


def test_patel_sobh_virtual_four_bar() -> None:
    at_12 = run(**FOURBAR_GRASHOF_EXAMPLES[2].inputs).result
    assert at_12["barker"]["class"] == "I-4"
    assert at_12["links"][2]["role"] == "output" and at_12["links"][2]["motion"] == "crank"
    at_7 = run(**FOURBAR_GRASHOF_EXAMPLES[3].inputs)
    assert at_7.result["grashof"] == "change-point"
    assert at_7.result["barker"] == {"class": "III-1", "code": "SCCC",
                                     "name": "change-point double-crank"}  # fmt: skip
    assert at_7.result["criterion"]["margin"] == 0.0
    assert at_7.notes[0].startswith("Change point: s + l = p + q = 22")
    case_2 = run(lengths=[15, 8, 14, 12], ground=3).result  # l2 shortest: a double rocker
    assert case_2["classification"] == "double-rocker"
    assert case_2["links"][2]["motion"] == "rocker"


def test_parallelogram_is_a_double_change_point() -> None:
    result = run(**FOURBAR_GRASHOF_EXAMPLES[4].inputs).result
    assert result["barker"]["code"] == "S2X"
    assert result["classification"] == "change-point"


def test_plots_false_gives_no_artifacts() -> None:
    assert run(lengths=[1, 2, 3, 4], ground=0, plots=False).artifacts == ()
