"""The client reads what a result's numbers are from the process description: the
command line prints every nested value with its symbol and unit (``criterion.margin``
in cm, not the key names of ``criterion``), and its reading of the declarations is the
service's (symbols as text, units with the job's length unit)."""

from __future__ import annotations

import pytest

from dexlab.cli.render import print_results, result_rows
from dexlab.quantities import ResultPaths, display_unit, plain_symbol
from tests.unit.families.conftest import RecordingContext
from worker import result_paths as declared
from worker.registry import default_registry

REGISTRY = default_registry()


def fig_3_in_cm() -> tuple[dict[str, object], dict[str, object]]:
    definition = REGISTRY.get("fourbar-grashof")
    assert definition is not None
    inputs = {"lengths": [30, 17, 18, 25], "ground": 0, "length_unit": "cm", "plots": False}
    spec = definition.inputs_model.model_validate(inputs)
    return dict(definition.run(spec, RecordingContext()).result), definition.describe()


def test_every_nested_value_is_a_row_with_its_symbol_and_unit() -> None:
    result, description = fig_3_in_cm()
    paths = ResultPaths.from_description(description, "cm")
    rows = {r[0]: r[1:] for r in result_rows(result, paths)}
    assert rows["criterion.margin"] == ("p + q - (s + l)", "-4", "cm")
    assert rows["criterion.shortest"] == ("", "1", "")
    assert rows["lengths"] == ("L_i", "[30, 17, 18, 25]", "cm")
    assert rows["links[].length"] == ("L_i", "[30, 17, 18, 25]", "cm")
    assert rows["barker.class"] == ("", "II-1", "")
    assert "criterion" not in rows and "notes" not in rows


def test_the_printed_table_shows_the_margin_in_cm(capsys: pytest.CaptureFixture[str]) -> None:
    result, description = fig_3_in_cm()
    document = {"jobID": "j-1", "processID": "fourbar-grashof", "result": result,
                "artifacts": []}  # fmt: skip
    print_results(document, description=description)
    line = next(li for li in capsys.readouterr().out.splitlines() if "criterion.margin" in li)
    assert line.split() == ["criterion.margin", "p", "+", "q", "-", "(s", "+", "l)", "-4", "cm"]
    print_results(document)  # an older service: no description, the values all the same
    line = next(li for li in capsys.readouterr().out.splitlines() if "criterion.margin" in li)
    assert line.split() == ["criterion.margin", "-4"]


def test_the_client_reads_every_declaration_as_the_service_does() -> None:
    for definition in REGISTRY:
        paths = ResultPaths.from_description(definition.describe(), "mm")
        for entry in definition.result_paths:
            shown = paths.find(entry.path)
            assert shown is not None, entry.path
            expected = declared.plain_symbol(entry.symbol) if entry.symbol else ""
            assert shown.symbol == expected == plain_symbol(entry.symbol or "")
            assert shown.unit == declared.display_unit(entry.unit, "mm")
            assert shown.unit == display_unit(entry.unit, "mm")


def test_paths_with_indices_read_as_every_element() -> None:
    paths = ResultPaths([{"path": "task_points[].d_z", "unit": "-", "symbol": "$d_z$",
                          "description": "d_z."},
                         {"path": "areas.reachable", "unit": "length^2", "symbol": "",
                          "description": "Area."},
                         {"path": "pareto[].objectives.*", "unit": "mixed", "symbol": "",
                          "description": "Keyed."}], "cm")  # fmt: skip
    found = paths.find("task_points[3].d_z")
    assert found is not None and (found.symbol, found.unit) == ("d_z", "")
    area = paths.find(("areas", "reachable"))
    assert area is not None and area.unit == "cm²"
    keyed = paths.find(("pareto", 0, "objectives", "links|sum"))
    assert keyed is not None and keyed.path == "pareto[].objectives.*"
    assert paths.find("task_points[].x") is None and paths.find("no such!") is None
