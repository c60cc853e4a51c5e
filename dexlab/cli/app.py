"""The command tree and the entry point that turns usage errors into one line.

Click (with Rich for tables and progress) rather than Typer: Typer's recent releases
carry their own private copy of Click, so handling usage errors ourselves would mean
importing Typer's private modules.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from importlib.metadata import PackageNotFoundError, version

import click

from dexlab.cli import jobs, keys, processes, reuse, server
from dexlab.cli.job_ids import AmbiguousJobId

__all__ = ["cli", "main"]


def _version() -> str:
    try:
        return version("dexlab")
    except PackageNotFoundError:  # running from a source tree without an install
        return "unknown"


@click.group(
    name="dexlab",
    context_settings={"help_option_names": ["-h", "--help"]},
)
@click.version_option(_version(), "--version", prog_name="dexlab", message="%(prog)s %(version)s")
def cli() -> None:
    """Manipulator kinematic-design service: run it, or talk to it."""


server.register(cli)
processes.register(cli)
jobs.register(cli)
keys.register(cli)
reuse.register(cli)


def main(argv: Sequence[str] | None = None) -> None:
    """Run the command; a usage error exits 2 with a one-line message on stderr."""
    try:
        code = cli.main(
            args=list(argv) if argv is not None else sys.argv[1:],
            prog_name="dexlab",
            standalone_mode=False,
        )
    except click.exceptions.NoArgsIsHelpError as exc:  # "dexlab" alone: the help
        sys.stderr.write(exc.format_message() + "\n")
        raise SystemExit(2) from None
    except AmbiguousJobId as exc:  # the candidates, one per line
        sys.stderr.write(f"dexlab: {exc.format_message()}\n")
        raise SystemExit(exc.exit_code) from None
    except click.UsageError as exc:
        hint = f" (try '{exc.ctx.command_path} --help')" if exc.ctx is not None else ""
        message = " ".join(exc.format_message().split())
        sys.stderr.write(f"dexlab: {message}{hint}\n")
        raise SystemExit(2) from None
    except click.ClickException as exc:
        sys.stderr.write(f"dexlab: {' '.join(exc.format_message().split())}\n")
        raise SystemExit(exc.exit_code) from None
    except click.exceptions.Abort:
        sys.stderr.write("dexlab: aborted\n")
        raise SystemExit(130) from None
    raise SystemExit(code if isinstance(code, int) else 0)
