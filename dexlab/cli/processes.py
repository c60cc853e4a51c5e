"""``dexlab processes`` and ``dexlab describe ID``: what the service can run."""

from __future__ import annotations

import click

from dexlab.cli.client_options import client_options, open_client, reported_errors
from dexlab.cli.render import print_description, print_json, print_processes

__all__ = ["register"]


@click.command()
@client_options
def processes(url: str, api_key: str | None, as_json: bool) -> None:
    """List the processes the service runs."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        found = client.processes()
    print_json(found) if as_json else print_processes(found)


@click.command()
@click.argument("process_id", metavar="ID")
@client_options
def describe(process_id: str, url: str, api_key: str | None, as_json: bool) -> None:
    """Describe a process: its inputs, worked examples (numbered for --example) and limits."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        doc = client.describe(process_id)
    print_json(doc) if as_json else print_description(doc)


def register(group: click.Group) -> None:
    """Add ``processes`` and ``describe`` to the ``dexlab`` command."""
    group.add_command(processes)
    group.add_command(describe)
