"""A process's input JSON Schema as rows of a table a person can read.

One row per input, nested inputs under their parent (``grid.points_per_axis``), each
variant of a union named (``trajectory (PolylineTrajectory).points``), array items as
``chains[]``.  ``$ref``s are resolved against the schema's ``$defs``; a definition
met again inside itself is not expanded twice.

Units come from the ``x-unit`` keyword where the model declares one (``length``: the
job's length unit), else from the naming convention (``*_deg``: degrees, ``*_s``:
seconds).
"""

from __future__ import annotations

import json
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["InputRow", "input_rows", "unit_of"]

Schema = Mapping[str, Any]


@dataclass(frozen=True)
class InputRow:
    """One input: where it sits, what it takes, and what it means."""

    name: str
    depth: int
    type: str
    unit: str
    default: str
    range: str
    description: str
    required: bool


def _number(value: Any) -> str:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return json.dumps(value)
    if isinstance(value, int):
        return str(value)
    text = f"{value:.6g}" if abs(value) >= 100_000 else f"{value:.12g}"
    return text.replace("e+0", "e").replace("e-0", "e-").replace("e+", "e")


class _Resolver:
    def __init__(self, root: Schema) -> None:
        self.defs: Mapping[str, Any] = root.get("$defs", {})

    def resolve(self, schema: Schema) -> tuple[Schema, str]:
        """The schema a ``$ref`` points at (merged with the referring keywords) and the
        definition's name ("" for an inline schema)."""
        ref = schema.get("$ref")
        if not isinstance(ref, str) or not ref.startswith("#/$defs/"):
            return schema, ""
        name = ref.removeprefix("#/$defs/")
        target = self.defs.get(name, {})
        merged = {**target, **{k: v for k, v in schema.items() if k != "$ref"}}
        return merged, str(target.get("title") or name)


def _alternatives(schema: Schema) -> tuple[list[Schema], bool]:
    """The non-null alternatives of an ``anyOf``/``oneOf`` (nested ones flattened; or
    the schema itself), and whether null is allowed."""
    options = schema.get("anyOf") or schema.get("oneOf")
    if not options:
        return [schema], schema.get("type") == "null"
    real: list[Schema] = []
    nullable = False
    for option in options:
        inner, inner_nullable = _alternatives(option)
        nullable = nullable or inner_nullable
        real += [o for o in inner if o.get("type") != "null"]
    return real, nullable


def unit_of(name: str, schema: Schema) -> str:
    """The unit of an input: its ``x-unit`` (also inside an ``anyOf``), or by name."""
    for candidate in (schema, *(schema.get("anyOf") or ()), *(schema.get("oneOf") or ())):
        unit = candidate.get("x-unit")
        if isinstance(unit, str) and unit:
            return "length units" if unit == "length" else unit
    if name.endswith("_deg"):
        return "deg"
    if name.endswith("_s"):
        return "s"
    return ""


def _range(schema: Schema) -> list[str]:
    parts: list[str] = []
    if "enum" in schema:
        parts.append("one of " + ", ".join(_number(v) for v in schema["enum"]))
    if "const" in schema:
        parts.append("exactly " + _number(schema["const"]))
    low = ("≥", schema["minimum"]) if "minimum" in schema else None
    if "exclusiveMinimum" in schema:
        low = (">", schema["exclusiveMinimum"])
    high = ("≤", schema["maximum"]) if "maximum" in schema else None
    if "exclusiveMaximum" in schema:
        high = ("<", schema["exclusiveMaximum"])
    if low and high:
        parts.append(
            f"{_number(low[1])} {'≤' if low[0] == '≥' else '<'} x {high[0]} {_number(high[1])}"
        )
    elif low or high:
        op, bound = low or high  # type: ignore[misc]
        parts.append(f"{op} {_number(bound)}")
    for lo_key, hi_key, what in (
        ("minItems", "maxItems", "items"),
        ("minProperties", "maxProperties", "entries"),
        ("minLength", "maxLength", "characters"),
    ):
        lo, hi = schema.get(lo_key), schema.get(hi_key)
        if lo is not None and lo == hi:
            parts.append(f"{lo} {what}")
        elif lo is not None or hi is not None:
            parts.append(f"{lo if lo is not None else 0}–{hi if hi is not None else '∞'} {what}")
    if "pattern" in schema:
        parts.append(f"matches {schema['pattern']}")
    if "x-max-ratio" in schema:
        parts.append(f"longest ≤ {_number(schema['x-max-ratio'])} × shortest")
    return parts


class _Walker:
    def __init__(self, root: Schema) -> None:
        self.resolver = _Resolver(root)
        self.length_unit = "length_unit" in root.get("properties", {})

    def type_text(self, schema: Schema) -> str:
        """``number``, ``[3 × number]``, ``list of [2 × number] or null``, ``object``;
        a union of objects by their definitions' names."""
        options, nullable = _alternatives(schema)
        texts = [self._one_type(o, named=len(options) > 1) for o in options]
        text = " or ".join(dict.fromkeys(t for t in texts if t)) or "any"
        return f"{text} or null" if nullable else text

    def _one_type(self, schema: Schema, *, named: bool) -> str:
        schema, name = self.resolver.resolve(schema)
        if schema.get("type") == "object" and "patternProperties" in schema:
            values = [self.type_text(v) for v in schema["patternProperties"].values()]
            return "map of name → " + " or ".join(values)
        if schema.get("type") == "object" or "properties" in schema:
            return name if named and name else "object"
        kind = schema.get("type")
        if kind == "array":
            prefix = schema.get("prefixItems")
            if prefix:
                items = dict.fromkeys(self.type_text(p) for p in prefix)
                if len(items) == 1:
                    return f"[{len(prefix)} × {next(iter(items))}]"
                return "[" + ", ".join(self.type_text(p) for p in prefix) + "]"
            items_schema = schema.get("items")
            return f"list of {self.type_text(items_schema)}" if items_schema else "list"
        if isinstance(kind, list):
            return " or ".join(str(k) for k in kind)
        return str(kind or "")

    def _ranges(self, schema: Schema) -> str:
        options, _ = _alternatives(schema)
        parts = _range(schema)
        for option in options:
            resolved, _ = self.resolver.resolve(option)
            if resolved is not schema:
                parts += _range(resolved)
            for item in resolved.get("prefixItems") or ():
                inner = "; ".join(_range(item))
                if inner and f"each {inner}" not in parts:
                    parts.append(f"each {inner}")
            items = resolved.get("items")
            if isinstance(items, Mapping) and not self.resolver.resolve(items)[1]:
                inner = self._ranges(items)
                if inner:
                    parts.append(f"each {inner}")
        return "; ".join(dict.fromkeys(parts))

    def _unit(self, name: str, schema: Schema, inherited: str) -> str:
        unit = unit_of(name, schema) or inherited
        if unit == "length units" and self.length_unit:
            return "length (length_unit)"
        return unit

    def rows(
        self, schema: Schema, prefix: str, depth: int, seen: frozenset[str], unit: str = ""
    ) -> Iterator[InputRow]:
        """Rows of the properties of ``schema`` (an object), under ``prefix``; ``unit``:
        the parent's, which its fields share unless they say otherwise."""
        required = set(schema.get("required", ()))
        for name, prop in schema.get("properties", {}).items():
            path = f"{prefix}{name}"
            row = InputRow(
                name=path,
                depth=depth,
                type=self.type_text(prop),
                unit=self._unit(name, prop, unit),
                default=json.dumps(prop["default"]) if "default" in prop else "",
                range=self._ranges(prop),
                description=str(prop.get("description", "")),
                required=name in required,
            )
            yield row
            yield from self.nested(prop, path, depth + 1, seen, row.unit)

    def nested(
        self, schema: Schema, path: str, depth: int, seen: frozenset[str], unit: str
    ) -> Iterator[InputRow]:
        """Rows of the objects inside an input (its variants, its list items)."""
        options, _ = _alternatives(schema)
        objects = []
        for option in options:
            resolved, name = self.resolver.resolve(option)
            if name in seen:
                continue
            if resolved.get("type") == "array" and isinstance(resolved.get("items"), Mapping):
                yield from self.nested(resolved["items"], f"{path}[]", depth, seen, unit)
            elif "properties" in resolved:
                objects.append((resolved, name))
        for resolved, name in objects:
            label = f"{path} ({name})" if len(objects) > 1 and name else path
            yield from self.rows(resolved, f"{label}.", depth, seen | {name}, unit)


def input_rows(schema: Schema) -> list[InputRow]:
    """Every input of a process's JSON Schema, nested ones after their parent."""
    walker = _Walker(schema)
    return list(walker.rows(schema, "", 0, frozenset()))
