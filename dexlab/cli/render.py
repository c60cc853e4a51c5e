"""What the client commands print: Rich tables for people, JSON for scripts, and errors
as a short block on stderr.  Text from the service is never read as Rich markup."""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import click
from rich.console import Console
from rich.table import Table
from rich.text import Text

from dexlab.cli.job_table import duration_s, duration_text, status_table
from dexlab.documents import Artifact, JobStatus
from dexlab.errors import DexlabError, InvalidInputs
from dexlab.quantities import ResultPaths, ResultQuantity

__all__ = [
    "print_description",
    "print_error",
    "print_json",
    "print_processes",
    "print_results",
    "print_status",
    "print_status_table",
    "result_rows",
    "summarise",
]

#: Result members shown as notes rather than in the table.
_NOTE_MEMBERS = ("notes", "paper_errata")


def _console() -> Console:
    """Stdout; wide when it is not a terminal (a pipe or a file: nothing to fit)."""
    console = Console(highlight=False)
    if not console.is_terminal and "COLUMNS" not in os.environ:
        console = Console(highlight=False, width=160)
    return console


def print_json(document: Any) -> None:
    """``document`` as indented JSON on stdout."""
    click.echo(json.dumps(document, indent=2, ensure_ascii=False))


def summarise(value: Any, width: int = 72) -> str:
    """A value in one line: itself when short, else its shape."""
    text = json.dumps(value, ensure_ascii=False)
    if len(text) <= width:
        return text
    if isinstance(value, list):
        return f"[{len(value)} items] {text[: width - 20]}…"
    if isinstance(value, dict):
        keys = ", ".join(str(k) for k in value)
        return "{" + (keys if len(keys) < width else keys[: width - 2] + "…") + "}"
    return text[: width - 1] + "…"


def print_processes(processes: Sequence[Mapping[str, Any]]) -> None:
    table = Table(title="Processes", title_justify="left")
    table.add_column("ID", no_wrap=True, style="bold")
    table.add_column("Title")
    for process in processes:
        table.add_row(Text(str(process.get("id", ""))), Text(str(process.get("title", ""))))
    _console().print(table)


def _inputs_table(schema: Mapping[str, Any]) -> Table:
    required = set(schema.get("required") or [])
    table = Table(title="Inputs", title_justify="left")
    table.add_column("Name", no_wrap=True, style="bold")
    table.add_column("Type")
    table.add_column("Description")
    for name, prop in (schema.get("properties") or {}).items():
        kind = str(prop.get("type") or ("one of" if "anyOf" in prop or "oneOf" in prop else ""))
        if name in required:
            kind += " (required)"
        elif "default" in prop:
            kind += f" = {summarise(prop['default'], 20)}"
        table.add_row(Text(name), Text(kind), Text(str(prop.get("description") or "")))
    return table


def print_description(doc: Mapping[str, Any]) -> None:
    """A process: what it does, its inputs, worked examples (by number) and limits."""
    console = _console()
    console.print(Text(f"{doc.get('id')}: {doc.get('title', '')}", style="bold"))
    console.print(Text(str(doc.get("description") or "")))
    console.print(_inputs_table(doc.get("inputs") or {}))
    examples = Table(title="Worked examples (dexlab run ID --example N)", title_justify="left")
    examples.add_column("N", justify="right")
    examples.add_column("Example")
    for number, example in enumerate(doc.get("examples") or []):
        examples.add_row(str(number), Text(str(example.get("title") or "")))
    console.print(examples)
    limits = doc.get("limits") or {}
    if limits:
        console.print(Text("Limits: " + ", ".join(f"{k} {v}" for k, v in limits.items())))


def _status_rows(status: JobStatus) -> list[tuple[str, str]]:
    doc = status.document
    rows = [
        ("job", status.job_id),
        ("process", status.process_id),
        ("status", status.status),
        ("progress", f"{status.progress}%"),
        ("message", status.message),
    ]
    rows += [(key, str(doc[key])) for key in ("created", "started", "finished") if doc.get(key)]
    took = duration_s(doc)
    if took is not None:
        rows.append(("duration", duration_text(took)))
    if doc.get("expires"):
        rows.append(("expires", str(doc["expires"])))
    if "attempts" in doc:
        rows.append(("attempts", f"{doc['attempts']} of {doc.get('max_attempts', '?')}"))
    if status.error:
        rows.append(("error", f"{status.error.get('title', '')}: {status.error.get('detail', '')}"))
    return rows


def print_status(status: JobStatus) -> None:
    table = Table(show_header=False, box=None)
    table.add_column(style="bold")
    table.add_column()
    for key, value in _status_rows(status):
        table.add_row(key, Text(value))
    _console().print(table)


def print_status_table(statuses: Sequence[JobStatus], more: bool = False) -> None:
    """Jobs, one line each within 80 columns (see :mod:`dexlab.cli.job_table`);
    ``more``: the listing was cut at the limit."""
    console = _console()
    console.print(status_table(statuses))
    if more:
        console.print("More jobs than shown: --limit N shows more, --limit 0 all.")


#: Nesting of records inside records shown as rows of their own (deeper: as JSON).
_MAX_RECORD_DEPTH = 4
#: One row of a result: its place, its symbol, its value and its unit.
ResultRow = tuple[str, str, str, str]


def _rounded(value: Any) -> Any:
    """Numbers to 6 significant digits (whole ones without a decimal point), for text."""
    if isinstance(value, float) and value == value and abs(value) != float("inf"):
        short = float(f"{value:.6g}")
        return int(short) if short.is_integer() and abs(short) < 1e15 else short
    if isinstance(value, list):
        return [_rounded(v) for v in value]
    if isinstance(value, Mapping):
        return {k: _rounded(v) for k, v in value.items()}
    return value


def _value_text(value: Any) -> str:
    """A value as shown: numbers to 6 significant digits, text as itself, a list or an
    object as short JSON (summarised when long)."""
    if isinstance(value, str):
        return value if len(value) <= 72 else value[:71] + "…"
    return summarise(_rounded(value))


def _leaf(value: Any, steps: tuple[str | None, ...]) -> tuple[str | None, ...] | None:
    """The place of the numbers in ``value``: ``[]`` per level of list; None if none."""
    while isinstance(value, list):
        steps = (*steps, None)
        value = next((v for v in value if v is not None), None)
        if value is None:
            return steps
    is_number = isinstance(value, int | float) and not isinstance(value, bool)
    return steps if is_number else None


def _labels(
    name: str, value: Any, steps: tuple[str | None, ...], paths: ResultPaths
) -> tuple[str, str]:
    """(symbol, unit) of the numbers in ``value`` at ``steps``; the symbol is left out
    where it only repeats the key."""
    leaf = _leaf(value, steps)
    found: ResultQuantity | None = None if leaf is None else paths.find(leaf)
    if found is None:
        return "", ""
    key = name.rsplit(".", 1)[-1].removesuffix("[]")
    return ("" if found.symbol == key else found.symbol), found.unit


def _records(
    records: list[Any], name: str, steps: tuple[str | None, ...], paths: ResultPaths, depth: int
) -> list[ResultRow]:
    """A list of records as one row per member: its values across the records."""
    keys = dict.fromkeys(k for r in records if isinstance(r, Mapping) for k in r)
    rows: list[ResultRow] = []
    for key in keys:
        column = [r.get(key) if isinstance(r, Mapping) else None for r in records]
        inner, label = (*steps, str(key)), f"{name}.{key}"
        present = [c for c in column if c is not None]
        if present and depth < _MAX_RECORD_DEPTH and all(isinstance(c, Mapping) for c in present):
            rows += _records(column, label, inner, paths, depth + 1)
        elif present and depth < _MAX_RECORD_DEPTH and all(_is_records(c) for c in present):
            rows += _records_of_records(column, label, (*inner, None), paths)
        else:
            first = present[0] if present else None
            symbol, unit = _labels(label, first, inner, paths)
            rows.append((label, symbol, _value_text(column), unit))
    return rows


def _is_records(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, Mapping) for v in value)


def _records_of_records(
    column: list[Any], name: str, steps: tuple[str | None, ...], paths: ResultPaths
) -> list[ResultRow]:
    """Records inside records (each chain's loops): one row per member of the inner
    records, its values grouped by outer record."""
    inner = [c if isinstance(c, list) else [] for c in column]
    keys = dict.fromkeys(k for c in inner for r in c if isinstance(r, Mapping) for k in r)
    rows: list[ResultRow] = []
    for key in keys:
        grouped = [[r.get(key) if isinstance(r, Mapping) else None for r in c] for c in inner]
        label = f"{name}[].{key}"
        first = next((v for group in grouped for v in group if v is not None), None)
        symbol, unit = _labels(label, first, (*steps, str(key)), paths)
        rows.append((label, symbol, _value_text(grouped), unit))
    return rows


def result_rows(result: Mapping[str, Any], paths: ResultPaths) -> list[ResultRow]:
    """Every member of a result, nested ones by their dotted place (``criterion.margin``),
    a list of records one row per member (``links[].length``: every link's), each with
    its symbol and unit where the process declares them."""
    rows: list[ResultRow] = []

    def walk(value: Any, name: str, steps: tuple[str | None, ...]) -> None:
        if isinstance(value, Mapping) and value:
            for key, item in value.items():
                walk(item, f"{name}.{key}" if name else str(key), (*steps, str(key)))
        elif isinstance(value, list) and value and all(isinstance(v, Mapping) for v in value):
            rows.extend(_records(value, f"{name}[]", (*steps, None), paths, 1))
        else:
            symbol, unit = _labels(name, value, steps, paths)
            rows.append((name, symbol, _value_text(value), unit))

    walk({k: v for k, v in result.items() if k not in _NOTE_MEMBERS}, "", ())
    return rows


def print_results(
    document: Mapping[str, Any],
    downloaded: Sequence[Path] = (),
    description: Mapping[str, Any] | None = None,
) -> None:
    """A result document: every number with its symbol and unit (from the process
    ``description``'s ``result_paths``, if given), the notes and the files."""
    console = _console()
    result = document.get("result") or {}
    console.print(Text(f"Job {document.get('jobID')} ({document.get('processID')}): results",
                       style="bold"))  # fmt: skip
    unit = result.get("length_unit")
    paths = ResultPaths.from_description(description or {}, unit if isinstance(unit, str) else None)
    table = Table(box=None, pad_edge=False)
    for column in ("Result", "Symbol", "Value", "Unit"):
        table.add_column(
            column, no_wrap=column == "Result", style="bold" if column == "Result" else None
        )
    for name, symbol, value, shown_unit in result_rows(result, paths):
        table.add_row(Text(name), Text(symbol), Text(value), Text(shown_unit))
    console.print(table)
    for note in result.get("notes") or []:
        console.print(Text(f"• {note}"))
    files = [Artifact.from_document(a) for a in document.get("artifacts") or []]
    if files:
        listing = Table(title="Files (dexlab results JOB --download DIR)", title_justify="left")
        for column in ("Name", "Type", "Size", "Title"):
            listing.add_column(column)
        for f in files:
            listing.add_row(Text(f.name), Text(f.media_type), f"{f.size:,}", Text(f.title))
        console.print(listing)
    if downloaded:
        folder = downloaded[0].parent
        console.print(Text(f"Wrote {len(downloaded)} files to {folder}"))


def print_error(error: DexlabError, as_json: bool = False) -> None:
    """An error as a short block on stderr: one line, then the fields it names; with
    ``as_json`` the problem document also goes to stdout."""
    if as_json:
        print_json(error.problem)
    lines = [f"dexlab: {error.message}"]
    if isinstance(error, InvalidInputs):
        lines += [f"  {e.get('field', '?')}: {e.get('message', '')}" for e in error.errors]
    if error.problem.get("jobID") and error.slug not in ("", "about:blank"):
        lines.append(f"  job {error.problem['jobID']}, problem type {error.type}")
    if error.retry_after is not None:
        lines.append(f"  retry after {error.retry_after:g} s")
    click.echo("\n".join(lines), err=True)
