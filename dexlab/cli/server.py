"""``dexlab serve`` and ``dexlab worker``: run the service (they import it when run)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

import click

__all__ = ["register"]

F = TypeVar("F", bound=Callable[..., Any])


def _store_options(command: F) -> F:
    """The options both server commands take."""
    for option in reversed(
        (
            click.option(
                "--data-dir",
                type=click.Path(file_okay=False, path_type=Path),
                help="Where the SQLite store lives (./data).",
            ),
            click.option(
                "--store-url", help="Job store URL (default sqlite:///<data-dir>/jobs.db)."
            ),
            click.option(
                "--broker-url",
                help="Celery broker (redis://... or amqp://...); unset: the local worker pool.",
            ),
            click.option(
                "--workers",
                type=click.IntRange(min=0),
                help="Worker processes (default: the CPU count; 0: none).",
            ),
            click.option(
                "--log-level",
                type=click.Choice(["debug", "info", "warning", "error"], case_sensitive=False),
                help="How much to log (info).",
            ),
        )
    ):
        command = option(command)
    return command


def _settings_problem(command: str, exc: Exception) -> SystemExit:
    """A setting the service refused, as one line per setting (never its value: it may
    be a secret); exit status 2."""
    lines = []
    for error in getattr(exc, "errors", lambda: [])():
        field = ".".join(str(part) for part in error.get("loc", ())) or "settings"
        lines.append(
            f"dexlab {command}: invalid setting DEXLAB_{field.upper()}: {error.get('msg', '')}"
        )
    sys.stderr.write("\n".join(lines or [f"dexlab {command}: invalid settings: {exc}"]) + "\n")
    return SystemExit(2)


def _given(**options: Any) -> dict[str, Any]:
    return {name: value for name, value in options.items() if value is not None}


@click.command()
@click.option("--host", help="Address to bind (127.0.0.1).")
@click.option("--port", type=click.IntRange(0, 65535), help="Port to listen on (8000).")
@_store_options
def serve(**options: Any) -> None:
    """Run the HTTP API with a local worker pool (or the API alone with a broker)."""
    from pydantic import ValidationError

    # cli: `dexlab serve` and `dexlab worker` load the service only when they run
    from service.cli import serve as run_server

    try:
        run_server(_given(**options))
    except ValidationError as exc:
        raise _settings_problem("serve", exc) from None


@click.command()
@_store_options
def worker(log_level: str | None, **options: Any) -> None:
    """Run worker processes alone against a store (a Celery worker with a broker)."""
    from pydantic import ValidationError

    # cli: `dexlab serve` and `dexlab worker` load the service only when they run
    from service.cli import run_worker

    try:
        code = run_worker(_given(**options), log_level or "info")
    except ValidationError as exc:
        raise _settings_problem("worker", exc) from None
    if code:
        raise SystemExit(code)


def register(group: click.Group) -> None:
    """Add the server commands to the ``dexlab`` command."""
    group.add_command(serve)
    group.add_command(worker)
