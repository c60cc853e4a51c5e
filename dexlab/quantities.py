"""What the numbers of a result are, read from the process description's
``result_paths``: each number's symbol, unit and meaning, for the command line and for
scripts.

::

    paths = ResultPaths.from_description(client.describe("fourbar-grashof"), "cm")
    paths.find("criterion.margin")     # ResultQuantity(unit='cm', symbol='p + q - (s + l)', ...)
    paths.find("links[2].length")      # an index reads as '[]': links[].length

Symbols come as mathtext (``$\\alpha_1$``) and are shown as text (``α₁``); a unit
``length`` is the job's ``length_unit``, ``length^2`` its square (``cm²``); a pure
number (``-``) or values of mixed units show no unit.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["ResultPaths", "ResultQuantity", "display_unit", "plain_symbol"]

Steps = tuple[str | None, ...]
_DECLARED = re.compile(r"^(\*|[A-Za-z_][A-Za-z0-9_]*)((?:\[\d*\])*)$")


@dataclass(frozen=True)
class ResultQuantity:
    """One number of a result as shown: its declared ``path``, ``unit`` ("" for a pure
    number), ``symbol`` (text, "" for none) and ``description``."""

    path: str
    unit: str
    symbol: str
    description: str


def _steps(path: str) -> Steps | None:
    """``task_points[3].d_z`` -> ("task_points", None, "d_z"); None if not a path."""
    steps: list[str | None] = []
    for part in path.split("."):
        match = _DECLARED.match(part)
        if match is None:
            return None
        steps.append(match.group(1))
        steps.extend([None] * match.group(2).count("["))
    return tuple(steps)


class ResultPaths:
    """A process's result paths with a job's length unit, looked up by the place of a
    number: a path (``links[2].length``) or its steps (keys, None for list elements)."""

    def __init__(self, entries: Iterable[Mapping[str, Any]], length_unit: str = "units") -> None:
        self._exact: dict[Steps, ResultQuantity] = {}
        self._keyed: list[tuple[Steps, ResultQuantity]] = []
        for entry in entries:
            steps = _steps(str(entry.get("path", "")))
            if steps is None:
                continue
            symbol = str(entry.get("symbol") or "")
            quantity = ResultQuantity(
                str(entry["path"]),
                display_unit(str(entry.get("unit", "-")), length_unit),
                plain_symbol(symbol) if symbol else "",
                str(entry.get("description") or ""),
            )
            if "*" in steps:
                self._keyed.append((steps, quantity))
            else:
                self._exact[steps] = quantity

    @classmethod
    def from_description(
        cls, description: Mapping[str, Any], length_unit: str | None = None
    ) -> ResultPaths:
        """From ``GET /v1/processes/{id}`` (none if the service publishes none)."""
        entries = description.get("result_paths")
        return cls(entries if isinstance(entries, list) else (), length_unit or "units")

    def find(self, place: str | Sequence[str | int | None]) -> ResultQuantity | None:
        """The quantity at ``place``, if the process declares it."""
        steps = _steps(place) if isinstance(place, str) else tuple(place)
        if steps is None:
            return None
        key = tuple(None if isinstance(s, int) else s for s in steps)
        if key in self._exact:
            return self._exact[key]
        for pattern, quantity in self._keyed:
            if len(pattern) == len(key) and all(
                p == k or (p == "*" and isinstance(k, str))
                for p, k in zip(pattern, key, strict=False)
            ):
                return quantity
        return None


_SUPERSCRIPTS = str.maketrans("0123456789n", "⁰¹²³⁴⁵⁶⁷⁸⁹ⁿ")
_SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def display_unit(unit: str, length_unit: str) -> str:
    """A declared unit as shown beside a number: ``length^2`` in cm -> ``cm²``; ""
    for a pure number (``-``) or mixed units."""
    if unit in ("-", "mixed"):
        return ""
    text = length_unit + unit.removeprefix("length") if unit.startswith("length") else unit
    base, _, power = text.partition("^")
    return base + power.translate(_SUPERSCRIPTS)


_LETTERS = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε",
    "zeta": "ζ", "eta": "η", "theta": "θ", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν",
    "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ", "chi": "χ",
    "psi": "ψ", "omega": "ω", "sum": "∑", "Delta": "Δ", "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ",
    "Omega": "Ω", "Lambda": "Λ", "Theta": "Θ", "Gamma": "Γ", "Pi": "Π", "prime": "′",
    "min": "min", "max": "max", "det": "det", "cos": "cos", "sin": "sin", "ln": "ln",
    "log": "log",
}  # fmt: skip
_TEXT = re.compile(r"\\math(?:rm|it|bf|sf)\{([^{}]*)\}")
_COMMAND = re.compile(r"\\([A-Za-z]+)")
_SCRIPT = re.compile(r"([_^])(?:\{([^{}]*)\}|([^\s{}]))")


def _script(match: re.Match[str]) -> str:
    body = match.group(2) if match.group(2) is not None else match.group(3)
    if match.group(1) == "^":
        return body.translate(_SUPERSCRIPTS) if body in ("2", "3", "4", "n") else f"^({body})"
    return body.translate(_SUBSCRIPTS) if body.isdigit() else f"_{body}"


def plain_symbol(symbol: str) -> str:
    """A mathtext symbol as text: ``$\\alpha_1$`` -> ``α₁``, ``$\\beta_{\\min}$`` ->
    ``β_min``, ``$1/\\kappa^2$`` -> ``1/κ²``; a command it does not know stays as written."""
    text = symbol.strip()
    if len(text) >= 2 and text.startswith("$") and text.endswith("$"):
        text = text[1:-1]
    text = _TEXT.sub(lambda m: m.group(1), text)
    text = text.replace(r"\,", " ").replace(r"\ ", " ").replace(r"\!", "")
    text = _COMMAND.sub(lambda m: _LETTERS.get(m.group(1), m.group(0)), text)
    text = _SCRIPT.sub(_script, text)
    return text.replace("'", "′").replace("{", "").replace("}", "")
