"""What the numbers of a result document are: every numeric path a process reports,
with its unit, its symbol and what it means.

A process declares one :class:`ResultPathInfo` per numeric place of its result, in the
result-path syntax of design studies (:mod:`worker.studies.paths`): ``[]`` for every
element of a list, no indices and no reductions (``task_points[].d_z``); a ``*`` step
stands for every key of a mapping whose keys the request chooses (a study's
``parameters`` and ``objectives``, keyed by paths).  ``GET /v1/processes/{id}``
publishes them as ``result_paths``; the job pages, the command line and the design
studies' files and figures label numbers with them.

**Units** are a closed set (:data:`RESULT_UNITS`), written as the data files write
them: ``-`` for a pure number; ``length`` where the job's ``length_unit`` applies (as
the input schemas' ``x-unit``), ``length^2`` for an area; ``deg``.  :func:`unit_text`
spells one out for a job (``length^2`` in cm is ``cm^2``).

**Symbols** are mathtext (``$d_z$``, ``$1/\\kappa$``), drawn as such in figures;
:func:`plain_symbol` writes one as Unicode text for pages and terminals
(``$\\alpha_1$`` -> ``α₁``, ``$\\beta_{\\min}$`` -> ``β_min``).  ``""``: a count or a
setting without a symbol of its own.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace

__all__ = [
    "RESULT_UNITS",
    "ResultPathInfo",
    "ResultPathTable",
    "declared_steps",
    "display_unit",
    "plain_symbol",
    "prefixed",
    "unit_text",
]

#: Every unit a result path may have, and what it means.
RESULT_UNITS: Mapping[str, str] = {
    "-": "a pure number: a ratio, an index, a count, a rank or a code",
    "length": "the job's length_unit",
    "length^2": "an area: the job's length_unit squared",
    "length^3": "a volume: the job's length_unit cubed",
    "length^4": "the job's length_unit to the fourth power (a chain's Q, eq 3)",
    "length^n": "the job's length_unit to the power n, the number of lengths multiplied "
    "(a chain's P, eq 1)",
    "l1": "a length in units of the proximal arm l1 (planar2dof-optimisation is normalised "
    "as the paper is)",
    "l1^2": "an area in units of l1 squared",
    "deg": "degrees",
    "deg^2": "square degrees: an area in a plane of two angles",
    "mixed": "values of different units side by side (the description says which)",
}

#: A step of a declared path: a key, None for every element of a list, "*" for every key.
Step = str | None
_STEP = re.compile(r"^(\*|[A-Za-z_][A-Za-z0-9_]*)((?:\[\])*)$")


@dataclass(frozen=True)
class ResultPathInfo:
    """One numeric place of a result: ``path`` (``task_points[].d_z``), ``unit`` (one of
    :data:`RESULT_UNITS`), ``symbol`` (mathtext, or ``""``) and ``description``.

    ``optional`` says, for a path no worked example reports, when the process reports
    it (the tests check every other declaration against the examples' results).
    """

    path: str
    unit: str
    symbol: str
    description: str
    optional: str = ""

    def describe(self, *, kernel: bool = False) -> dict[str, str | bool]:
        """The entry as published in a process description; ``kernel``: a design
        study evaluates it in its process's batched kernel (:mod:`worker.study_kernels`),
        published as ``"kernel": true`` (absent otherwise)."""
        entry: dict[str, str | bool] = {
            "path": self.path,
            "unit": self.unit,
            "symbol": self.symbol,
            "description": self.description,
        }
        if kernel:
            entry["kernel"] = True
        return entry


def prefixed(prefix: str, entries: Iterable[ResultPathInfo]) -> tuple[ResultPathInfo, ...]:
    """``entries`` under ``prefix`` (``"optimum"`` + ``min_dz`` -> ``optimum.min_dz``)."""
    return tuple(replace(e, path=f"{prefix}.{e.path}") for e in entries)


def declared_steps(path: str) -> tuple[Step, ...]:
    """``"task_points[].d_z"`` -> ``("task_points", None, "d_z")``; ValueError for a
    path that is not a declaration (indices and reductions have no place in one)."""
    steps: list[Step] = []
    for part in path.split("."):
        match = _STEP.match(part)
        if match is None:
            raise ValueError(f"{path!r}: {part!r} is not a declared step (a name or '*', "
                             "then any number of '[]')")  # fmt: skip
        steps.append(match.group(1))
        steps.extend([None] * (len(match.group(2)) // 2))
    return tuple(steps)


class ResultPathTable:
    """A process's declarations, looked up by the steps of a place in its result: keys,
    and None (or an index) for a list element."""

    def __init__(self, entries: Iterable[ResultPathInfo]) -> None:
        self._exact: dict[tuple[Step, ...], ResultPathInfo] = {}
        self._keyed: list[tuple[tuple[Step, ...], ResultPathInfo]] = []
        for entry in entries:
            steps = declared_steps(entry.path)
            if "*" in steps:
                self._keyed.append((steps, entry))
            else:
                self._exact[steps] = entry

    def find(self, steps: Sequence[str | int | None]) -> ResultPathInfo | None:
        """The declaration of the place ``steps`` names, if any."""
        key = tuple(None if isinstance(s, int) else s for s in steps)
        found = self._exact.get(key)
        if found is not None:
            return found
        for pattern, entry in self._keyed:
            pairs = zip(pattern, key, strict=False)
            if len(pattern) == len(key) and all(
                p == k or (p == "*" and isinstance(k, str)) for p, k in pairs
            ):
                return entry
        return None


def unit_text(unit: str, length_unit: str) -> str:
    """A unit as the data files write it for a job: ``length^2`` in ``cm`` -> ``cm^2``."""
    if unit.startswith("length"):
        return length_unit + unit.removeprefix("length")
    return unit


_SUPERSCRIPTS = str.maketrans("0123456789n", "⁰¹²³⁴⁵⁶⁷⁸⁹ⁿ")


def display_unit(unit: str, length_unit: str) -> str:
    """A unit as pages and terminals show it beside a number: ``cm²``; ``""`` for a
    pure number or mixed units (nothing one unit can say)."""
    if unit in ("-", "mixed"):
        return ""
    base, _, power = unit_text(unit, length_unit).partition("^")
    return base + power.translate(_SUPERSCRIPTS)


#: Mathtext commands as text: Greek letters, operators' names, the sum sign, the prime.
_COMMANDS = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε",
    "zeta": "ζ", "eta": "η", "theta": "θ", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν",
    "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ", "chi": "χ",
    "psi": "ψ", "omega": "ω", "sum": "∑", "Delta": "Δ", "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ",
    "Omega": "Ω", "Lambda": "Λ", "Theta": "Θ", "Gamma": "Γ", "Pi": "Π", "prime": "′",
    **{name: name for name in ("min", "max", "det", "cos", "sin", "ln", "log")},
}  # fmt: skip
_SUBSCRIPT_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_COMMAND = re.compile(r"\\([A-Za-z]+)")
_TEXT = re.compile(r"\\math(?:rm|it|bf|sf)\{([^{}]*)\}")
_SCRIPT = re.compile(r"([_^])(?:\{([^{}]*)\}|([^\s{}]))")


def _command(match: re.Match[str]) -> str:
    name = match.group(1)
    if name not in _COMMANDS:
        raise ValueError(f"plain_symbol does not know the mathtext command \\{name}")
    return _COMMANDS[name]


def _script(match: re.Match[str]) -> str:
    kind, body = match.group(1), match.group(2) if match.group(2) is not None else match.group(3)
    if kind == "^":
        return body.translate(_SUPERSCRIPTS) if body in ("2", "3", "4", "n") else f"^({body})"
    if body.isdigit():
        return body.translate(_SUBSCRIPT_DIGITS)
    return f"_{body}"


def plain_symbol(symbol: str) -> str:
    """A mathtext symbol as Unicode text: ``$\\alpha_1$`` -> ``α₁``, ``$d_z$`` -> ``d_z``,
    ``$1/\\kappa^2$`` -> ``1/κ²``, ``$\\mathrm{mean}(\\eta)$`` -> ``mean(η)``.  Knows
    the mathtext the declarations use; ValueError for any other command."""
    text = symbol.strip()
    if text.startswith("$") and text.endswith("$") and len(text) >= 2:
        text = text[1:-1]
    text = _TEXT.sub(lambda m: m.group(1), text)
    text = text.replace(r"\,", " ").replace(r"\ ", " ").replace(r"\!", "")
    text = _COMMAND.sub(_command, text)
    text = _SCRIPT.sub(_script, text)
    return text.replace("'", "′").replace("{", "").replace("}", "")
