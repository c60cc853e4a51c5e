"""``dexlab reuse invalidate PROCESS [--key K]``: stop stored results being reused.

An admin key's command: the jobs stay, with their results; new submissions of the
process (of result key ``K`` only, with ``--key``) compute afresh.  Exit status as for
the job commands: 0 done, 1 refused or unreachable, 2 a usage error.
"""

from __future__ import annotations

import click

from dexlab.cli.client_options import client_options, open_client, reported_errors
from dexlab.cli.render import print_json

__all__ = ["register"]


@click.group()
def reuse() -> None:
    """Reuse of stored results (admins)."""


@reuse.command()
@click.argument("process_id", metavar="PROCESS")
@click.option("--key", metavar="K", help="Only this result key (a result's provenance.result_key).")
@client_options  # fmt: skip
def invalidate(process_id: str, key: str | None, url: str, api_key: str | None,
               as_json: bool) -> None:  # fmt: skip
    """Stop the stored results of PROCESS from answering new jobs (deletes no job)."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        done = client.invalidate_reuse(process_id, key)
    if as_json:
        print_json(done)
        return
    which = f"result key {key}" if key else "every result key"
    count = int(done.get("invalidated", 0))
    click.echo(
        f"{count} stored result{'' if count == 1 else 's'} of {process_id} ({which}) "
        "will not be reused."
    )


def register(group: click.Group) -> None:
    """Add ``reuse`` to the ``dexlab`` command."""
    group.add_command(reuse)
