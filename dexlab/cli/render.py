"""What the client commands print: Rich tables for people, JSON for scripts, and errors
as a short block on stderr.  Text from the service is never read as Rich markup."""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import click
from rich.console import Console
from rich.table import Table
from rich.text import Text

from dexlab.documents import Artifact, JobStatus
from dexlab.errors import DexlabError, InvalidInputs

__all__ = [
    "print_description",
    "print_error",
    "print_json",
    "print_processes",
    "print_results",
    "print_status",
    "print_status_table",
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


def print_status_table(statuses: Iterable[JobStatus], more: bool = False) -> None:
    """Jobs, one per row; ``more``: the listing was cut at the limit."""
    table = Table(title="Jobs, newest first", title_justify="left")
    for column in ("Job", "Process", "Status", "Progress", "Created", "Message"):
        table.add_column(column, no_wrap=column in ("Job", "Status"))
    for status in statuses:
        created = str(status.document.get("created") or "")[:19].replace("T", " ")
        table.add_row(Text(status.job_id), Text(status.process_id), Text(status.status),
                      f"{status.progress}%", created, Text(status.message))  # fmt: skip
    console = _console()
    console.print(table)
    if more:
        console.print("More jobs than shown: --limit N shows more, --limit 0 all.")


def print_results(document: Mapping[str, Any], downloaded: Sequence[Path] = ()) -> None:
    """A result document: its members (long ones summarised), notes and files."""
    console = _console()
    result = document.get("result") or {}
    console.print(Text(f"Job {document.get('jobID')} ({document.get('processID')}): results",
                       style="bold"))  # fmt: skip
    table = Table(show_header=False)
    table.add_column(style="bold", no_wrap=True)
    table.add_column()
    for key, value in result.items():
        if key not in _NOTE_MEMBERS:
            table.add_row(Text(str(key)), Text(summarise(value)))
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
