"""What every client command shares: ``--url``, ``--api-key`` and ``--json``, the client
they open, and how a failure from the service ends the command (exit 1, no traceback)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, TypeVar

import click

from dexlab.cli.render import print_error
from dexlab.client import Client
from dexlab.connection import DEFAULT_URL
from dexlab.errors import DexlabError

__all__ = ["client_options", "open_client", "reported_errors"]

F = TypeVar("F", bound=Callable[..., Any])


def client_options(command: F) -> F:
    """Add ``--url``, ``--api-key`` and ``--json`` to a command."""
    for option in reversed(
        (
            click.option(
                "--url",
                envvar="DEXLAB_URL",
                default=DEFAULT_URL,
                show_default=True,
                show_envvar=True,
                help="The dexlab service.",
            ),
            click.option(
                "--api-key",
                envvar="DEXLAB_API_KEY",
                show_envvar=True,
                help="API key, sent as 'Authorization: Bearer'.",
            ),
            click.option(
                "--json", "as_json", is_flag=True, help="Print JSON documents (for scripts)."
            ),
        )
    ):
        command = option(command)
    return command


def open_client(url: str, api_key: str | None) -> Client:
    """A client for the command; a malformed ``--url`` is a usage error."""
    try:
        return Client(url, api_key or None)
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="'--url'") from None


@contextmanager
def reported_errors(as_json: bool) -> Iterator[None]:
    """Turn a dexlab error into its message on stderr (and, with ``--json``, its problem
    document on stdout) and exit status 1."""
    try:
        yield
    except DexlabError as error:
        print_error(error, as_json)
        raise SystemExit(1) from None
