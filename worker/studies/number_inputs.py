"""Whether an input path can hold a number, by a process's published input schema.

A study varies numbers: a varied path must lead, through the process's JSON Schema, to
a place that takes a number (``"type": "number"`` or ``"integer"``, or anything).  The
walk follows ``$ref``, ``anyOf`` and ``oneOf`` (any alternative may do), a lone
``allOf``, object ``properties``, ``patternProperties`` and ``additionalProperties``,
and array ``prefixItems``, ``items`` and ``maxItems``; a keyword it does not know
constrains nothing, so a path is refused only where the schema rules it out.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from typing import Any

from worker.studies.paths import InputPath, parse_input_path
from worker.studies.spec import StudySpec

__all__ = ["takes_number", "unvariable_paths"]

#: Deepest ``$ref`` / ``anyOf`` nesting followed (a schema referring to itself ends here).
_MAX_DEPTH = 32
_ANYTHING: dict[str, Any] = {}


def takes_number(schema: Mapping[str, Any], path: InputPath) -> bool:
    """Whether some document valid under ``schema`` may hold a number at ``path``
    (``("chains", 3, "lengths", 0)``)."""
    nodes = list(_alternatives(schema, schema, 0))
    for step in path:
        nodes = [alt for node in nodes for alt in _alternatives(schema, _child(node, step), 0)]
    return any(_numeric(node) for node in nodes)


def unvariable_paths(spec: StudySpec, schema: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Field errors for the study's varied paths at which ``schema`` (the process's
    inputs) holds no number: a name it does not take, a flag, a text, a list, a mapping."""
    where = "inputs.vary" if spec.vary is not None else "inputs.sample.bounds"
    return [
        {"field": f"{where}.{name}", "type": "value_error",
         "message": f"{spec.process} takes no number at '{name}' (see its input schema)"}
        for name in spec.designs.names
        if not takes_number(schema, parse_input_path(name))
    ]  # fmt: skip


def _alternatives(root: Mapping[str, Any], node: Any, depth: int) -> Iterator[Mapping[str, Any]]:
    """The plain schemas ``node`` may be: references resolved, unions flattened."""
    if node is None:
        return
    if not isinstance(node, Mapping) or depth > _MAX_DEPTH:
        yield _ANYTHING  # ``true`` or a nesting too deep to follow: anything goes
        return
    ref = node.get("$ref")
    if isinstance(ref, str):
        yield from _alternatives(root, _resolve(root, ref), depth + 1)
        return
    union = node.get("anyOf", node.get("oneOf"))
    if isinstance(node.get("allOf"), list) and len(node["allOf"]) == 1:
        union = node["allOf"]  # one schema wrapped (older generators do it for a $ref)
    if isinstance(union, list):
        for member in union:
            yield from _alternatives(root, member, depth + 1)
        return
    yield node


def _resolve(root: Mapping[str, Any], ref: str) -> Any:
    """The schema a local reference (``#/$defs/GridSpec``) names; anything if none."""
    if not ref.startswith("#/"):
        return _ANYTHING
    node: Any = root
    for part in ref[2:].split("/"):
        if not isinstance(node, Mapping) or part not in node:
            return _ANYTHING
        node = node[part]
    return node


def _types(node: Mapping[str, Any]) -> set[str] | None:
    declared = node.get("type")
    if isinstance(declared, str):
        return {declared}
    return set(declared) if isinstance(declared, list) else None


def _child(node: Mapping[str, Any], step: str | int) -> Any:
    """The schema of ``node``'s member ``step``; None if ``node`` has no such member."""
    types = _types(node)
    if isinstance(step, str):
        if types is not None and "object" not in types:
            return None
        properties = node.get("properties", {})
        if step in properties:
            return properties[step]
        for pattern, schema in node.get("patternProperties", {}).items():
            if re.search(pattern, step):
                return schema
        extra = node.get("additionalProperties", True)
        return None if extra is False else extra
    if types is not None and "array" not in types:
        return None
    most = node.get("maxItems")
    if isinstance(most, int) and step >= most:
        return None
    prefix = node.get("prefixItems", [])
    if step < len(prefix):
        return prefix[step]
    items = node.get("items", True)
    return None if items is False else items


def _numeric(node: Mapping[str, Any]) -> bool:
    if "const" in node:
        return _is_number(node["const"])
    if isinstance(node.get("enum"), list):
        return any(_is_number(value) for value in node["enum"])
    types = _types(node)
    return types is None or bool(types & {"number", "integer"})


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)
