"""JSON laid out for a person to edit in a form's text box."""

from __future__ import annotations

import json
from typing import Any

__all__ = ["compact_json"]


def compact_json(value: Any, indent: int = 0, width: int = 72) -> str:
    """JSON laid out for a person to edit: a value that fits ``width`` on one line,
    else one member (or item) per line, indented by two."""
    flat = json.dumps(value, ensure_ascii=False)
    if len(flat) + indent <= width or not isinstance(value, dict | list) or not value:
        return flat
    pad = " " * (indent + 2)
    if isinstance(value, dict):
        members = [
            f"{pad}{json.dumps(str(k), ensure_ascii=False)}: {compact_json(v, indent + 2, width)}"
            for k, v in value.items()
        ]
        return "{\n" + ",\n".join(members) + "\n" + " " * indent + "}"
    items = [f"{pad}{compact_json(v, indent + 2, width)}" for v in value]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
