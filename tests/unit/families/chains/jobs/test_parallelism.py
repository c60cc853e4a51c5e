"""The chain-parallelism job: the paper's Figs 2, 3 and 4 end to end (docs/methods/chains.md)."""

from __future__ import annotations

import json
from typing import Any

import pytest
from matplotlib.figure import Figure

from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.contract import JobOutcome
from worker.families.chains import CHAIN_PARALLELISM
from worker.families.chains.examples import CHAIN_PARALLELISM_EXAMPLES, FIG_4A
from worker.families.chains.jobs import parallelism
from worker.families.chains.specs import ChainParallelismSpec

CHAIN_KEYS = {
    "name", "form", "links", "joints", "independent_loops", "mobility", "dimensions",
    "total_length", "P", "P_normalized", "loops", "Q", "Q_normalized", "arrangements",
    "rank",
}  # fmt: skip
LOOP_KEYS = {"index", "peripheral", "sides", "lengths", "products", "deviations", "Q"}


@pytest.fixture(autouse=True)
def fast_chain_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(parallelism, "figure_artifacts", unrendered_artifacts)


def run(inputs: dict[str, Any]) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = ChainParallelismSpec.model_validate(inputs)
    return CHAIN_PARALLELISM.run(spec, ctx), ctx


def run_example(index: int) -> JobOutcome:
    return run(dict(CHAIN_PARALLELISM_EXAMPLES[index].inputs))[0]


def by_name(outcome: JobOutcome) -> dict[str, dict[str, Any]]:
    return {entry["name"]: entry for entry in outcome.result["chains"]}


def ranking(outcome: JobOutcome, key: str) -> list[tuple[int, str]]:
    return [(e["rank"], e["name"]) for e in outcome.result["ranking"][key]["order"]]


def test_result_is_json_and_complete() -> None:
    outcome, ctx = run(dict(CHAIN_PARALLELISM_EXAMPLES[2].inputs))
    result = json.loads(json.dumps(outcome.result))
    assert set(result) == {"chains", "ranking", "method", "length_unit"}
    for entry in result["chains"]:
        assert set(entry) == CHAIN_KEYS
        assert all(set(loop) == LOOP_KEYS for loop in entry["loops"])
    assert [a.name for a in outcome.artifacts] == [
        "chain_graphs.png", "chain_graphs.svg", "parallelism_comparison.png",
        "parallelism_comparison.svg",
    ]  # fmt: skip
    assert ctx.percents[0] == 0.0 and ctx.percents[-1] == 100.0
    assert ctx.percents == sorted(ctx.percents)


def test_each_chain_carries_its_place_in_both_rankings() -> None:
    outcome = run_example(0)
    for key in ("by_P", "by_Q"):
        places = {e["name"]: e["rank"] for e in outcome.result["ranking"][key]["order"]}
        assert {e["name"]: e["rank"][key] for e in outcome.result["chains"]} == places
    assert by_name(outcome)["Fig 2d"]["rank"] == {"by_P": 2, "by_Q": 4}


def test_fig_2_numbers_and_rankings() -> None:
    outcome = run_example(0)
    chains = by_name(outcome)
    assert {n: e["P"] for n, e in chains.items()} == {
        "Fig 2a": 50625, "Fig 2b": 40000, "Fig 2c": 40000, "Fig 2d": 45900, "Fig 2e": 45900,
    }  # fmt: skip
    assert {n: e["Q"] for n, e in chains.items()} == {
        "Fig 2a": 0, "Fig 2b": 0, "Fig 2c": 100000, "Fig 2d": 34592, "Fig 2e": 15650,
    }  # fmt: skip
    assert chains["Fig 2d"]["loops"][0]["deviations"] == [36, 120, -20, -136]
    assert chains["Fig 2e"]["loops"][0]["deviations"] == [90, 10, -85, -15]
    assert chains["Fig 2d"]["P_normalized"] == pytest.approx(0.0035417, abs=5e-8)
    assert ranking(outcome, "by_P") == [(1, "Fig 2a"), (2, "Fig 2d"), (2, "Fig 2e"),
                                        (4, "Fig 2b"), (4, "Fig 2c")]  # fmt: skip
    assert ranking(outcome, "by_Q") == [(1, "Fig 2a"), (1, "Fig 2b"), (3, "Fig 2e"),
                                        (4, "Fig 2d"), (5, "Fig 2c")]  # fmt: skip
    assert outcome.result["ranking"]["by_Q"]["measure"] == "Q"
    reading = outcome.result["ranking"]["by_Q"]["reading"]
    assert "Smaller Q: more parallel" in reading and "Most parallel: Fig 2a, Fig 2b (tied)" in (
        reading
    )
    assert "Most uniformly rigid: Fig 2a" in outcome.result["ranking"]["by_P"]["reading"]


def test_fig_2_arrangements() -> None:
    chains = by_name(run_example(0))
    arrangements = chains["Fig 2d"]["arrangements"]
    assert arrangements["count"] == 3 and arrangements["given_rank"] == 3
    assert [(a["rank"], a["lengths"], a["Q"], a["given"]) for a in arrangements["ranked"]] == [
        (1, [18, 15, 17, 10], 15650, False),  # Fig 2e (reflected)
        (2, [18, 10, 15, 17], 30402, False),
        (3, [18, 15, 10, 17], 34592, True),
    ]
    assert arrangements["ranked"][0]["sides"] == ["1", "2", "4", "3"]
    assert chains["Fig 2e"]["arrangements"]["given_rank"] == 1
    assert chains["Fig 2a"]["arrangements"]["count"] == 1
    assert chains["Fig 2c"]["arrangements"]["most_parallel"] == ["1", "3", "2", "4"]


def test_fig_2_notes_give_printed_and_correct_values() -> None:
    notes = "\n".join(run_example(0).all_notes)
    assert "36, 120, 20, 126" in notes and "36, 120, -20, -136" in notes
    assert "90, 10, 85, 75" in notes and "90, 10, -85, -15" in notes
    assert "1/60, 1/60, 17/60, 18/60" in notes and "15/60" in notes
    assert "'Fig 2e is more parallel than Fig 2d' holds: Q 15650 < 34592" in notes
    assert "'Fig 2b is more parallel than Fig 2c' holds" in notes
    assert "Fig 2d: the given arrangement ranks 3 of 3 by Q" in notes


def test_fig_2d_against_fig_3() -> None:
    outcome = run_example(1)
    chains = by_name(outcome)
    assert chains["Fig 3"]["P_normalized"] == pytest.approx(0.0034979, abs=5e-8)
    assert ranking(outcome, "by_P") == [(1, "Fig 2d"), (2, "Fig 3")]
    assert outcome.result["ranking"]["by_Q"]["measure"] == "Q_normalized"  # sums 60 and 90
    notes = "\n".join(outcome.all_notes)
    assert "0.0349" in notes and "0.0034979" in notes
    assert "ranking.by_Q uses Q_normalized" in notes


def test_fig_4_numbers() -> None:
    outcome = run_example(2)
    chains = by_name(outcome)
    a, b = chains["Fig 4a"], chains["Fig 4b"]
    assert [loop["products"] for loop in a["loops"]] == [
        [66, 110, 60, 36], [56, 56, 35, 50, 70], [99, 110, 90, 63, 35, 50, 90],
    ]  # fmt: skip
    assert [loop["Q"] for loop in a["loops"]] == [5912, 1262, 3940] and a["Q"] == 11114
    assert [loop["Q"] for loop in b["loops"]] == [6632, 1702, 1780] and b["Q"] == 10114
    assert [loop["peripheral"] for loop in a["loops"]] == [False, False, True]
    assert (a["links"], a["joints"], a["independent_loops"], a["mobility"]) == (7, 8, 2, 2)
    assert len(a["dimensions"]) == 11 and a["total_length"] == 88
    assert a["dimensions"][0] == {"side": "1.a", "length": 6.0, "normalized": 6 / 88}
    assert a["P"] == b["P"] == 6 * 7 * 9 * 11 * 10 * 6 * 8 * 9 * 7 * 5 * 10
    # every polygon side is one dimension: 11 lengths, each divided by their sum 88
    assert a["P_normalized"] == b["P_normalized"] == pytest.approx(a["P"] / 88**11, rel=1e-12)
    assert a["arrangements"] is None
    assert ranking(outcome, "by_P") == [(1, "Fig 4a"), (1, "Fig 4b")]
    assert ranking(outcome, "by_Q") == [(1, "Fig 4b"), (2, "Fig 4a")]


def test_fig_4_notes() -> None:
    notes = run_example(2).all_notes
    text = "\n".join(notes)
    assert "11214" in text and "5912 + 1262 + 3940 = 11114" in text
    assert "9538" in text and "10474" in text and "= 10114" in text
    assert "'Fig 4b is more parallel than Fig 4a' holds: Q 10114 < 11114" in text
    mobility = [n for n in notes if "single-DOF" in n]
    assert mobility == [
        "The paper calls its Fig 4 chains single-DOF; 7 links and 8 joints give mobility "
        "3 x 6 - 2 x 8 = 2 by Grübler-Kutzbach."
    ]  # once, not once per chain


def test_recognition_ignores_rotation_reflection_and_names() -> None:
    mirrored = {"name": "mine", "lengths": [15, 17, 10, 18]}  # Fig 2e read the other way
    outcome, _ = run({"chains": [mirrored]})
    assert any("is the paper's Fig 2e" in n for n in outcome.all_notes)
    outcome, _ = run({"chains": [{"name": "other", "lengths": [18, 10, 15, 17]}]})
    assert not any("paper" in n for n in outcome.all_notes)


def test_structures_have_a_note() -> None:
    outcome, _ = run({"chains": [{"name": "triangle", "lengths": [3, 4, 5]}]})
    assert outcome.result["chains"][0]["mobility"] == 0
    assert any("a structure, not a mechanism" in n for n in outcome.all_notes)


def test_links_form_single_loop_gets_arrangements() -> None:
    chain = {"name": "quad", "links": {"g": 30, "a": 17, "c": 18, "b": 25},
             "loops": [["g", "a", "c", "b"]]}  # fmt: skip
    entry = run({"chains": [chain]})[0].result["chains"][0]
    assert entry["form"] == "links" and entry["loops"][0]["peripheral"] is True
    assert entry["arrangements"]["count"] == 3
    assert entry["arrangements"]["ranked"][0]["sides"] == ["g", "a", "b", "c"]


def test_plots_false_gives_no_artifacts() -> None:
    outcome, _ = run({"chains": [FIG_4A], "plots": False})
    assert outcome.artifacts == ()
    assert outcome.result["chains"][0]["Q"] == 11114


def test_graph_captions_give_q_in_its_unit(monkeypatch: pytest.MonkeyPatch) -> None:
    figures: dict[str, Figure] = {}

    def capture(fig: Figure, stem: str, title: str) -> Any:
        figures[stem] = fig
        return unrendered_artifacts(fig, stem, title)

    monkeypatch.setattr(parallelism, "figure_artifacts", capture)
    run_example(0)  # Fig. 2: five quadrangles in cm
    captions = {ax.get_title(): ax.get_xlabel() for ax in figures["chain_graphs"].axes}
    assert captions["Fig 2d"].endswith(r"$Q$ = 34592 cm$^4$")
    assert captions["Fig 2c"].endswith(r"$Q$ = 1$\times 10^{5}$ cm$^4$")
    assert all(caption.endswith("cm$^4$") for caption in captions.values())
