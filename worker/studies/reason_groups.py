"""A design study's infeasible designs grouped by reason, for its page and
``GET /v1/jobs/{jobID}/designs/reasons``: the study's ``infeasible_reasons`` with the
numbers their messages quote replaced by ``…``, so reasons that differ only in the
angles or lengths they quote are one group, with the designs of all of them counted.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from typing import Any

__all__ = ["NUMBER", "reason_groups", "reason_text"]

#: A number as messages quote it (``12``, ``-0.5``, ``1.2e-3``, ``'37.5'``), with a
#: unit sign glued to it (``37.5°``, ``12%``) kept out of the group's text too.
NUMBER = re.compile(r"""(['"]?)[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?[°%]?\1""")


def reason_text(message: str) -> str:
    """``message`` with every number it quotes replaced by ``…`` (its group's text)."""
    return NUMBER.sub("…", message)


def reason_groups(reasons: Iterable[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The study result's ``infeasible_reasons`` (each ``reason_code``,
    ``reason_field``, ``reason``, ``designs``) grouped by code, field and
    :func:`reason_text`: each group's ``reason`` (numbers as ``…``), ``example`` (its
    most frequent message), ``messages`` (distinct messages) and ``designs`` (their
    sum); most designs first."""
    groups: dict[tuple[str, str, str], dict[str, Any]] = {}
    for entry in reasons:
        code = str(entry.get("reason_code") or "")
        field_name = str(entry.get("reason_field") or "")
        message = str(entry.get("reason") or "")
        designs = int(entry.get("designs") or 0)
        key = (code, field_name, reason_text(message))
        group = groups.setdefault(key, {
            "reason_code": code, "reason_field": field_name, "reason": key[2],
            "example": message, "most": -1, "messages": 0, "designs": 0,
        })  # fmt: skip
        group["messages"] += 1
        group["designs"] += designs
        if designs > group["most"]:
            group["example"], group["most"] = message, designs
    ordered = sorted(groups.values(), key=lambda g: (-g["designs"], g["reason"]))
    return [{k: v for k, v in g.items() if k != "most"} for g in ordered]
