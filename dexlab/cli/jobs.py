"""``dexlab run``, ``status``, ``results``, ``jobs`` and ``cancel``: jobs from a terminal.

Exit status: 0 done; 1 the service refused the request, the job failed or was dismissed,
or the service could not be reached (one block on stderr: the problem and the fields it
names); 2 a usage error (one line), or a job ID prefix that starts several job IDs (the
candidates listed); 130 interrupted.  Wherever a command takes a job (``JOB``), any
unique prefix of its ID will do (:mod:`dexlab.cli.job_ids`).
"""

from __future__ import annotations

import json
from itertools import islice
from pathlib import Path
from typing import IO, Any

import click

from dexlab.cli.client_options import client_options, open_client, reported_errors
from dexlab.cli.job_ids import find_job
from dexlab.cli.render import print_json, print_results, print_status, print_status_table
from dexlab.cli.robot_option import RobotChoice, robot_options
from dexlab.client import Client
from dexlab.documents import example_inputs
from dexlab.errors import DexlabError
from dexlab.job import Job
from dexlab.progress import progress_display

__all__ = ["register"]

STATUSES = ("accepted", "running", "successful", "failed", "dismissed")


def _read_inputs(source: IO[str]) -> dict[str, Any]:
    """The inputs object of a JSON file (or the ``{"inputs": {...}}`` body around it)."""
    try:
        document = json.load(source)
    except ValueError as exc:
        raise click.BadParameter(f"not JSON: {exc}", param_hint="'--inputs'") from None
    if isinstance(document, dict) and set(document) == {"inputs"}:
        document = document["inputs"]
    if not isinstance(document, dict):
        raise click.BadParameter("must hold a JSON object (the inputs)", param_hint="'--inputs'")
    return document


class _Descriptions:
    """Process descriptions, each asked for once in a command (an example's inputs, then
    the units of its results)."""

    def __init__(self, client: Client) -> None:
        self._client = client
        self._known: dict[str, dict[str, Any]] = {}

    def get(self, process_id: str) -> dict[str, Any]:
        if process_id not in self._known:
            self._known[process_id] = self._client.describe(process_id)
        return self._known[process_id]

    def for_results(self, process_id: str) -> dict[str, Any] | None:
        """The description for labelling results; None if it cannot be read (the
        results are then shown without units)."""
        try:
            return self.get(process_id)
        except DexlabError:
            return None


def _inputs(descriptions: _Descriptions, process_id: str, source: IO[str] | None,
            example: int | None) -> dict[str, Any]:  # fmt: skip
    if source is None and example is None:
        raise click.UsageError("Give the inputs: --inputs FILE (or - for stdin) or --example N.")
    if source is not None and example is not None:
        raise click.UsageError("Give --inputs or --example, not both.")
    if source is not None:
        return _read_inputs(source)
    assert example is not None
    try:
        return example_inputs(process_id, descriptions.get(process_id), example)
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="'--example'") from None


def _finish(job: Job, directory: Path | None, as_json: bool, descriptions: _Descriptions) -> None:
    """Print a finished job's results, each number with its symbol and unit (and
    download its files)."""
    downloaded = job.download(directory) if directory is not None else []
    if as_json:
        document = dict(job.results())
        if directory is not None:
            document["downloaded"] = [str(p) for p in downloaded]
        print_json(document)
    else:
        description = descriptions.for_results(job.process_id)
        print_results(job.results(), downloaded, description)


def _wait_or_dismiss(job: Job, timeout: float | None) -> None:
    """Wait with a progress bar; on Ctrl-C, ask whether to dismiss the job."""
    try:
        click.echo(f"Job {job.id} submitted; waiting for it (Ctrl-C to stop).", err=True)
        job.wait(timeout, progress=progress_display(True, job.process_id))
    except KeyboardInterrupt:
        click.echo("", err=True)
        try:
            dismiss = click.confirm(f"Dismiss job {job.id}?", default=False, err=True)
        except click.Abort:
            dismiss = False
        if dismiss:
            job.cancel()
            click.echo(f"Job {job.id} dismissed.", err=True)
        else:
            click.echo(f"Job {job.id} goes on: dexlab status {job.id}", err=True)
        raise SystemExit(130) from None


@click.command()
@click.argument("process_id", metavar="ID")
@click.option(
    "--inputs",
    "source",
    type=click.File("r"),
    metavar="FILE|-",
    help="The inputs as a JSON object (a file, or - for stdin).",
)
@click.option(
    "--example",
    type=click.IntRange(min=0),
    metavar="N",
    help="Run worked example N (from 0; 'dexlab describe ID' lists them).",
)
@robot_options
@click.option("--wait", is_flag=True, help="Wait for the job, with a progress bar.")
@click.option(
    "--download",
    "directory",
    type=click.Path(file_okay=False, path_type=Path),
    help="Write the job's files into DIR (waits for the job).",
    metavar="DIR",
)
@click.option(
    "--timeout",
    type=click.FloatRange(min=0, min_open=True),
    metavar="SECONDS",
    help="Stop waiting after this long (the job goes on).",
)
@client_options  # fmt: skip
def run(process_id: str, source: IO[str] | None, example: int | None, robot: RobotChoice,
        wait: bool, directory: Path | None, timeout: float | None, url: str,
        api_key: str | None, as_json: bool) -> None:  # fmt: skip
    """Submit a job; with --wait (or --download), follow it and print its results.

    With --robot, a serial process studies your own arm: a URDF, a DH table (CSV) or
    a JSON file replaces the robot of the inputs (or of the example)."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        descriptions = _Descriptions(client)
        inputs = _inputs(descriptions, process_id, source, example)
        job = client.submit(process_id, robot.applied(inputs))
        if not (wait or directory is not None):
            if as_json:
                print_json(job.last_status.document)
            else:
                click.echo(f"Job {job.id} submitted ({job.last_status.status}).")
                click.echo(f"Follow it: dexlab status {job.id}   results: dexlab results {job.id}")
            return
        _wait_or_dismiss(job, timeout)
        _finish(job, directory, as_json, descriptions)


@click.command()
@click.argument("job_id", metavar="JOB")
@client_options
def status(job_id: str, url: str, api_key: str | None, as_json: bool) -> None:
    """Show a job's status."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        found = find_job(client, job_id).last_status
    print_json(found.document) if as_json else print_status(found)


@click.command()
@click.argument("job_id", metavar="JOB")
@click.option(
    "--download",
    "directory",
    type=click.Path(file_okay=False, path_type=Path),
    help="Write the job's files into DIR.",
    metavar="DIR",
)
@client_options  # fmt: skip
def results(job_id: str, directory: Path | None, url: str, api_key: str | None,
            as_json: bool) -> None:  # fmt: skip
    """Show a finished job's results (and download its files)."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        job = find_job(client, job_id)
        job.results()  # a job that has not ended: result-not-ready, exit 1
        _finish(job, directory, as_json, _Descriptions(client))


@click.command(name="jobs")
@click.option("--status", "status_filter", type=click.Choice(STATUSES), help="Only these.")
@click.option("--process", metavar="ID", help="Only jobs of this process.")
@click.option(
    "--limit",
    type=click.IntRange(min=0),
    default=50,
    show_default=True,
    help="Show at most this many (0: all).",
)
@client_options  # fmt: skip
def list_jobs(status_filter: str | None, process: str | None, limit: int, url: str,
              api_key: str | None, as_json: bool) -> None:  # fmt: skip
    """List jobs, newest first."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        found = client.jobs(status_filter, process, page_size=min(limit or 100, 100))
        shown = [job.last_status for job in (islice(found, limit + 1) if limit else found)]
    more = bool(limit) and len(shown) > limit
    shown = shown[:limit] if limit else shown
    if as_json:
        print_json([s.document for s in shown])
    else:
        print_status_table(shown, more)


@click.command()
@click.argument("job_id", metavar="JOB")
@client_options
def cancel(job_id: str, url: str, api_key: str | None, as_json: bool) -> None:
    """Dismiss a job: a queued job never runs, a running one stops, results are deleted."""
    with reported_errors(as_json), open_client(url, api_key) as client:
        found = find_job(client, job_id).cancel()
    if as_json:
        print_json(found.document)
    else:
        click.echo(f"Job {found.job_id} {found.status}.")


def register(group: click.Group) -> None:
    """Add the job commands to the ``dexlab`` command."""
    for command in (run, status, results, list_jobs, cancel):
        group.add_command(command)
