"""Inputs, costs and process definitions of the kinematic-chain jobs."""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import pytest
from pydantic import ValidationError

from worker.errors import InvalidInputs
from worker.families.chains import CHAIN_PARALLELISM, FOURBAR_GRASHOF
from worker.families.chains.costs import (
    CHAIN_COST_LIMIT,
    CHAIN_SYNC_COST_LIMIT,
    arrangement_count,
    chain_parallelism_cost,
    fourbar_grashof_cost,
)
from worker.families.chains.examples import FIG_2, FIG_4A, FIG_4B
from worker.families.chains.fourbar_spec import FourBarGrashofSpec
from worker.families.chains.specs import (
    ChainParallelismSpec,
    LoopChain,
    MultiLoopChain,
    PolygonalLink,
)
from worker.registry import default_registry
from worker.submission import validate_inputs

#: Fig 4a without link 7: a six-link Watt chain (mobility 1).
WATT: dict[str, Any] = {
    "name": "Watt",
    "links": {"1": {"sides": {"a": 6, "b": 7, "c": 9}}, "2": 11, "3": 10,
              "4": {"sides": {"a": 6, "b": 8, "c": 9}}, "5": 7, "6": 5},
    "loops": [["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6"],
              ["1.c", "2", "3", "4.c", "5", "6"]],
}  # fmt: skip


def loop(name: str, lengths: list[float]) -> dict[str, Any]:
    return {"name": name, "lengths": lengths}


def chains_spec(*chains: dict[str, Any], **inputs: Any) -> ChainParallelismSpec:
    return ChainParallelismSpec.model_validate({"chains": list(chains), **inputs})


def fig_4a(**changes: Any) -> dict[str, Any]:
    return {**json.loads(json.dumps(FIG_4A)), **changes}


def errors_of(call: Any) -> list[dict[str, Any]]:
    with pytest.raises(ValidationError) as info:
        call()
    return info.value.errors(include_url=False)


# -- valid inputs ------------------------------------------------------------------------


def test_both_chain_forms_are_accepted() -> None:
    spec = chains_spec(loop("q", [18, 15, 10, 17]), {**loop("r", [1, 2, 3, 4])})
    assert isinstance(spec.chains[0], LoopChain)
    assert spec.chains[0].lengths == (18.0, 15.0, 10.0, 17.0)
    spec = chains_spec(FIG_4A, FIG_4B)
    first = spec.chains[0]
    assert isinstance(first, MultiLoopChain)
    assert isinstance(first.links["1"], PolygonalLink) and first.links["2"] == 11.0
    assert first.loops[2] == ("1.c", "2", "3", "4.c", "5", "6", "7")
    assert spec.length_unit == "units" and spec.plots is True


def test_fig_4_chains_of_mobility_2_are_accepted() -> None:
    chains_spec(FIG_4A, FIG_4B)  # the paper's "single-DOF" chains have M = 2: not rejected


def test_spec_round_trips_through_json() -> None:
    spec = chains_spec(FIG_4A, FIG_4B, length_unit="cm", plots=False)
    assert ChainParallelismSpec.model_validate_json(spec.model_dump_json()) == spec


def test_models_are_frozen() -> None:
    spec = FourBarGrashofSpec.model_validate({"lengths": [1, 2, 3, 4], "ground": 0})
    with pytest.raises(ValidationError, match="frozen"):
        spec.ground = 1  # type: ignore[misc]


# -- invalid chains: 422 errors naming the loop or link ----------------------------------


def test_unknown_link_is_named_by_chain_and_loop() -> None:
    bad = fig_4a(loops=[["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6", "7"],
                        ["1.c", "2", "3", "4.c", "5", "9", "7"]])  # fmt: skip
    (error,) = errors_of(lambda: chains_spec(FIG_4B, bad))
    assert error["loc"] == ("chains", 1, "loops", 2)
    assert error["msg"] == "chains[1].loops[2]: link '9' is not defined"
    assert error["type"] == "chain_description"


def test_the_service_gets_the_field_and_the_message() -> None:
    bad = fig_4a(loops=[["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6", "9"],
                        ["1.c", "2", "3", "4.c", "5", "6", "7"]])  # fmt: skip
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(CHAIN_PARALLELISM, {"chains": [FIG_4B, bad]})
    assert info.value.errors == [{
        "field": "inputs.chains[1].loops[1]",
        "message": "chains[1].loops[1]: link '9' is not defined",
        "type": "chain_description",
    }]  # fmt: skip


CHAIN_ERRORS = [
    # an open loop: loop 1 stops at link 6, never returning to link 1 through link 7
    (fig_4a(loops=[["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6"],
                   ["1.c", "2", "3", "4.c", "5", "6", "7"]]),
     ("chains", 0, "loops", 1),
     "chains[0].loops[1]: does not close with the other loops: its joint '1'-'6' borders no "
     "other loop"),
    (fig_4a(loops=[["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6", "7"]]),
     ("chains", 0, "links", "1", "sides", "c"),
     "chains[0].links['1'].sides['c']: side 'c' of link '1' is in no loop"),
    (fig_4a(links={**FIG_4A["links"], "8": 4.0}), ("chains", 0, "links", "8"),
     "chains[0].links['8']: link '8' is in no loop"),
    (fig_4a(loops=[["1.a", "2", "3", "4"], ["1.b", "4.b", "5", "6", "7"],
                   ["1.c", "2", "3", "4.c", "5", "6", "7"]]),
     ("chains", 0, "loops", 0), "chains[0].loops[0]: link '4' is polygonal"),
    (fig_4a(links={**FIG_4A["links"], "2": 40.0}), ("chains", 0, "loops", 0),
     "chains[0].loops[0]: the loop cannot close: side '2' (40) is not shorter than the sum "
     "of the others (22)"),
    (fig_4a(links={**FIG_4A["links"], "1": {"sides": {"a": 6, "b": 7, "c": 20}}}),
     ("chains", 0, "links", "1"), "chains[0].links['1']: link '1' cannot be a triangle"),
    (loop("q", [1, 2, 30]), ("chains", 0, "loops", 0),
     "chains[0].loops[0]: the loop cannot close: side '3' (30) is not shorter"),
]  # fmt: skip


@pytest.mark.parametrize(("chain", "loc", "message"), CHAIN_ERRORS)
def test_invalid_chains_name_the_problem(chain: dict[str, Any], loc: tuple[Any, ...], message):
    errors = errors_of(lambda: chains_spec(chain))
    assert errors[0]["loc"] == loc
    assert errors[0]["msg"].startswith(message), errors[0]["msg"]


def test_every_bad_chain_is_reported() -> None:
    bad = fig_4a(loops=[["1.a", "2", "3", "4.a"], ["1.b", "4.b", "5", "6", "x"],
                        ["1.c", "2", "3", "4.c", "5", "6", "7"]])  # fmt: skip
    errors = errors_of(lambda: chains_spec(bad, FIG_4B, {**bad, "name": "again"}))
    assert [e["loc"][:2] for e in errors] == [("chains", 0), ("chains", 2)]


def test_mismatched_link_counts_are_rejected() -> None:
    (error,) = errors_of(lambda: chains_spec(FIG_4A, loop("Fig 2d", list(FIG_2["Fig 2d"]))))
    assert error["loc"] == ("chains", 1)
    assert error["msg"] == (
        "chains[1]: 'Fig 2d' has 4 links and mobility 1, but chains[0] 'Fig 4a' has 7 links "
        "and mobility 2; compare only chains with the same number of links and degrees of "
        "freedom"
    )


def test_mismatched_mobility_is_rejected() -> None:
    (error,) = errors_of(lambda: chains_spec(WATT, loop("hexagon", [3, 3, 3, 3, 3, 3])))
    assert "'hexagon' has 6 links and mobility 3, but chains[0] 'Watt' has 6 links and " \
           "mobility 1" in error["msg"]  # fmt: skip


def test_chain_names_must_be_unique() -> None:
    (error,) = errors_of(lambda: chains_spec(loop("q", [1, 2, 3, 4]), loop("q", [2, 2, 3, 4])))
    assert error["loc"] == ("chains", 1, "name")
    assert error["msg"] == "chains[1].name: 'q' is also the name of chains[0]; chain names " \
                           "must be unique"  # fmt: skip


FIELD_ERRORS = [
    ({"chains": []}, "chains must have 1 to 20 entries, not 0"),
    ({"chains": [loop(str(i), [1, 2, 3, 4]) for i in range(21)]}, "1 to 20 entries, not 21"),
    ({"chains": [loop("q", [1, 2, 3, 4, 5, 6, 7, 8, 9])]}, "lengths must have 3 to 8 entries"),
    ({"chains": [loop("q", [1, 2])]}, "lengths must have 3 to 8 entries, not 2"),
    ({"chains": [fig_4a(loops=[])]}, "loops must have 1 to 16 entries, not 0"),
    ({"chains": [fig_4a(loops=[[]])]}, "a loop must have 1 to 16 entries, not 0"),
    ({"chains": [fig_4a(links={**FIG_4A["links"], "2": "long"})]}, "a link must be a length"),
    ({"chains": [loop("q", [1, 2, -3, 4])]}, "greater than or equal to 0.000001"),
    ({"chains": [loop("q", [1, 2, float("nan"), 4])]}, "finite number"),
    ({"chains": [{"name": "q"}]}, "either 'lengths'"),
    ({"chains": [{**loop("q", [1, 2, 3]), "links": {}}]}, "either 'lengths'"),
    ({"chains": [fig_4a(links={**FIG_4A["links"], "1.x": 3})]}, "should match pattern"),
    ({"chains": [fig_4a(links={**FIG_4A["links"], "1": {"sides": {"a": 1, "b": 1}}})]},
     "at least 3 items"),
    ({"chains": [fig_4a(loops=[["1.a", "2", "3", "4.a.b"]])]}, "should match pattern"),
    ({"chains": [loop("q", [1, 2, 3, 4])], "colour": "red"}, "Extra inputs are not permitted"),
    ({"chains": [loop("q", [1, 2, 3, 4])], "length_unit": "$x$"}, "should match pattern"),
]  # fmt: skip


def test_one_bad_item_gives_one_error_at_its_place() -> None:
    bad_link = fig_4a(links={**FIG_4A["links"], "1": {"sides": {"a": -6, "b": 7, "c": 9}}})
    for chain, field in (
        (loop("q", [1, 2, -3, 4]), "inputs.chains[0].lengths[2]"),
        (bad_link, "inputs.chains[0].links[1].sides.a"),
    ):
        with pytest.raises(InvalidInputs) as info:
            validate_inputs(CHAIN_PARALLELISM, {"chains": [chain]})
        assert [e["field"] for e in info.value.errors] == [field]


@pytest.mark.parametrize(("inputs", "message"), FIELD_ERRORS)
def test_field_errors(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        ChainParallelismSpec.model_validate(inputs)


FOURBAR_ERRORS = [
    ({"lengths": [1, 2, 3], "ground": 0}, r"lengths needs four link lengths .*, not 3"),
    ({"lengths": [1, 2, 3, 0], "ground": 0}, "greater than or equal to 0.000001"),
    ({"lengths": [1, 2, 3, 4], "ground": 4}, "less than or equal to 3"),
    ({"lengths": [1, 2, 3, 4], "ground": -1}, "greater than or equal to 0"),
    ({"lengths": [1, 2, 3, 4]}, r"ground\n  Field required"),
    ({"lengths": [1, 2, 3, 4], "ground": 0.5}, "valid integer"),
    ({"lengths": [1, 2, 3, 4], "ground": True}, "valid integer"),
    ({"lengths": [1, 2, 3, 4], "ground": 0, "links": []}, "Extra inputs"),
]


@pytest.mark.parametrize(("inputs", "message"), FOURBAR_ERRORS)
def test_fourbar_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        FourBarGrashofSpec.model_validate(inputs)


@pytest.mark.parametrize(
    ("lengths", "index", "message"),
    [
        ([1, 10, 1, 1], 1, "link 1 (10) is not shorter than the sum of the other three (3)"),
        ([1, 1, 1, 3], 3, "link 3 (3) is not shorter than the sum of the other three (3)"),
        ([0.1, 0.2, 0.3, 0.6], 3, "link 3 (0.6) is not shorter"),  # flat only, in decimals
    ],
)
def test_fourbar_that_cannot_close_is_named(lengths: list[float], index: int, message: str):
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(FOURBAR_GRASHOF, {"lengths": lengths, "ground": 0})
    (error,) = info.value.errors
    assert error["field"] == f"inputs.lengths[{index}]"
    assert error["message"].startswith(f"lengths[{index}]: the loop cannot close: {message}")
    FourBarGrashofSpec.model_validate({"lengths": [1, 1, 1, 2.99], "ground": 0})  # it moves


# -- costs -------------------------------------------------------------------------------


def test_chain_cost_is_links_times_loops_plus_arrangements() -> None:
    assert chain_parallelism_cost(chains_spec(FIG_4A, FIG_4B)) == 2 * 7 * 3
    quads = chains_spec(*[loop(n, list(v)) for n, v in FIG_2.items()])
    assert chain_parallelism_cost(quads) == 5 * (4 + 3)
    octagon = chains_spec(loop("o", [1, 2, 3, 4, 5, 6, 7, 8]))
    assert chain_parallelism_cost(octagon) == 8 + 2520


def test_arrangement_counts() -> None:
    assert [arrangement_count(n) for n in range(3, 9)] == [1, 3, 12, 60, 360, 2520]


def test_every_valid_request_fits_the_cost_limit() -> None:
    largest = chains_spec(*[loop(str(i), [1, 2, 3, 4, 5, 6, 7, 8]) for i in range(20)])
    assert chain_parallelism_cost(largest) == CHAIN_COST_LIMIT == 50_560
    assert chain_parallelism_cost(chains_spec(FIG_4A, FIG_4B)) <= CHAIN_SYNC_COST_LIMIT


def test_fourbar_cost_is_one() -> None:
    assert fourbar_grashof_cost(FourBarGrashofSpec(lengths=(1, 2, 3, 4), ground=0)) == 1


# -- process definitions -----------------------------------------------------------------


@pytest.mark.parametrize("process", [CHAIN_PARALLELISM, FOURBAR_GRASHOF], ids=lambda p: p.id)
def test_process_definition(process: Any) -> None:
    description = json.loads(json.dumps(process.describe()))
    assert description["inputs"]["additionalProperties"] is False
    assert description["jobControlOptions"] == ["async-execute", "sync-execute", "dismiss"]
    assert 0 < process.sync_cost_limit <= process.cost_limit
    assert process.examples
    for example in process.examples:
        spec = process.inputs_model.model_validate(dict(example.inputs))
        assert process.cost(spec) <= process.sync_cost_limit


def test_public_field_names() -> None:
    assert set(ChainParallelismSpec.model_json_schema()["properties"]) == {
        "chains", "length_unit", "plots",
    }  # fmt: skip
    assert set(FourBarGrashofSpec.model_json_schema()["properties"]) == {
        "lengths", "ground", "length_unit", "plots",
    }  # fmt: skip
    assert set(LoopChain.model_fields) == {"name", "lengths"}
    assert set(MultiLoopChain.model_fields) == {"name", "links", "loops"}
    assert set(PolygonalLink.model_fields) == {"sides"}


def test_field_descriptions_are_published() -> None:
    for model in (ChainParallelismSpec, FourBarGrashofSpec, LoopChain, MultiLoopChain):
        assert all(field.description for field in model.model_fields.values()), model


def test_registered_in_the_default_registry() -> None:
    registry = default_registry()
    assert registry.get("chain-parallelism") is CHAIN_PARALLELISM
    assert registry.get("fourbar-grashof") is FOURBAR_GRASHOF


def test_import_does_no_heavy_work() -> None:
    code = (
        "import sys, worker.families.chains; "
        "print(sorted(m for m in ('matplotlib', 'scipy', "
        "'worker.families.chains.jobs.parallelism', "
        "'worker.families.chains.jobs.fourbar') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
