"""Whether a varied path can hold a number, read from a process's input schema."""

from __future__ import annotations

from typing import Any

import pytest

from worker.registry import default_registry
from worker.studies.number_inputs import takes_number
from worker.studies.paths import parse_input_path


def schema_of(process_id: str) -> dict[str, Any]:
    process = default_registry().get(process_id)
    assert process is not None
    return process.inputs_schema


@pytest.mark.parametrize(
    ("process_id", "path", "number"),
    [
        ("planar3r-dexterity-map", "links[0]", True),
        ("planar3r-dexterity-map", "links[3]", False),  # three links at most
        ("planar3r-dexterity-map", "links", False),  # the whole list
        ("planar3r-dexterity-map", "plots", False),  # a flag
        ("planar3r-dexterity-map", "length_unit", False),  # a text
        ("planar3r-dexterity-map", "lenghts[0]", False),  # no such input
        ("planar3r-dexterity-map", "grid.points_per_axis", True),  # through a $ref
        ("planar3r-dexterity-map", "grid.bounds[3]", True),  # an array or null
        ("planar3r-dexterity-map", "grid.bounds[4]", False),
        ("planar3r-dexterity-map", "trajectory.x_start", True),  # one of two models
        ("planar3r-dexterity-map", "trajectory.points[1][0]", True),
        ("planar3r-dexterity-map", "task_points[0][2]", False),  # a point is [x, y]
        ("chain-parallelism", "chains[3].lengths[0]", True),  # any number of chains
        ("chain-parallelism", "chains[3]", False),  # a chain is a mapping
        ("chain-parallelism", "chains[0].name", False),
        ("spm-conditioning-map", "alpha1_deg", True),
        ("spm-conditioning-map", "workspace.tilt_max_deg", True),
    ],
)
def test_paths_of_the_processes_schemas(process_id: str, path: str, number: bool) -> None:
    assert takes_number(schema_of(process_id), parse_input_path(path)) is number


SCHEMA: dict[str, Any] = {
    "$defs": {
        "Node": {
            "type": "object",
            "properties": {"value": {"type": "integer"}, "next": {"$ref": "#/$defs/Node"}},
            "additionalProperties": False,
        },
    },
    "type": "object",
    "properties": {
        "node": {"$ref": "#/$defs/Node"},
        "wrapped": {"allOf": [{"$ref": "#/$defs/Node"}]},
        "mode": {"enum": ["a", "b"]},
        "level": {"enum": [1, 2, 3]},
        "unit": {"const": "cm"},
        "anything": True,
        "table": {
            "type": "object",
            "patternProperties": {"^x[0-9]$": {"type": "number"}},
            "additionalProperties": {"type": "string"},
        },
        "pair": {
            "type": "array",
            "prefixItems": [{"type": "string"}, {"type": "number"}],
            "items": False,
        },
        "either": {"oneOf": [{"type": "null"}, {"type": "array", "items": {"type": "number"}}]},
    },
    "additionalProperties": False,
}


@pytest.mark.parametrize(
    ("path", "number"),
    [
        ("node.value", True),
        ("node.next.next.next.value", True),  # a schema that refers to itself
        ("node.next.label", False),
        ("wrapped.value", True),  # a lone allOf
        ("mode", False),
        ("level", True),  # an enum of numbers
        ("unit", False),
        ("anything", True),
        ("anything.deep[3].er", True),  # `true` allows anything below it
        ("table.x1", True),
        ("table.y", False),  # additionalProperties: a text
        ("pair[0]", False),
        ("pair[1]", True),
        ("pair[2]", False),  # items: false
        ("either[5]", True),
        ("missing", False),
    ],
)
def test_schema_keywords(path: str, number: bool) -> None:
    assert takes_number(SCHEMA, parse_input_path(path)) is number
