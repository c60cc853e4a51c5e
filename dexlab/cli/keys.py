"""``dexlab keys``: make, list and revoke API keys in a service's job store.

The commands open the store directly (``--data-dir`` or ``--store-url``, else
``DEXLAB_STORE_URL`` / ``DEXLAB_DATA_DIR`` as the server reads them), so a key made
here works at once on every API replica of that store.  A new key's secret is
printed once, alone on the last line of the output; the store keeps only its hash.
The store is imported when a command runs, never when the command line loads.
"""

from __future__ import annotations

from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import click

if TYPE_CHECKING:
    from worker.store.base import JobStore

__all__ = ["keys", "register"]

F = TypeVar("F", bound=Callable[..., Any])


def _store_options(command: F) -> F:
    command = click.option(
        "--store-url", help="The job store URL (default: DEXLAB_STORE_URL, else the data dir's)."
    )(command)
    return click.option(
        "--data-dir",
        type=click.Path(file_okay=False, path_type=Path),
        help="The data directory of an embedded store (./data).",
    )(command)


def _open(data_dir: Path | None, store_url: str | None, create: bool = False) -> JobStore:
    """The store the options name (an embedded one that does not exist yet is made
    only when ``create``); a store that cannot be opened ends the command with one
    line and exit status 1."""
    if data_dir is not None and store_url is not None:
        raise click.UsageError("give --data-dir or --store-url, not both")
    from pydantic import ValidationError

    # cli: the client's command line loads the store only for `dexlab keys`
    from service.config import Settings
    from worker.errors import DexlabError
    from worker.store import open_store

    options: dict[str, Any] = {"data_dir": data_dir, "store_url": store_url}
    try:
        settings = Settings(**{k: v for k, v in options.items() if v is not None})
        url = settings.resolved_store_url()
        path = Path(url.removeprefix("sqlite:///")) if url.startswith("sqlite:///") else None
        if path is not None and not path.exists():
            if not create:
                raise click.ClickException(
                    f"no job store at {path}: give the service's --data-dir or --store-url"
                )
            click.echo(f"(a new job store at {path}; start the service on it)", err=True)
        return open_store(url, retry_s=settings.store_retry_seconds)
    except (DexlabError, ValueError, ValidationError) as exc:
        raise click.ClickException(f"cannot open the job store: {_one_line(exc)}") from None


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


def _check_name(name: str) -> str:
    # cli: the client's command line loads the store only for `dexlab keys`
    from worker.store.api_keys import check_key_name

    try:
        return check_key_name(name)
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="'NAME'") from None


def _when(epoch: float | None) -> str:
    if epoch is None:
        return "—"
    return datetime.fromtimestamp(epoch, tz=UTC).strftime("%Y-%m-%d %H:%M:%S")


@click.group()
def keys() -> None:
    """Make, list and revoke the API keys of a service."""


@keys.command()
@click.argument("name")
@click.option("--admin", is_flag=True, help="An admin key: sees and dismisses every job.")
@_store_options
def create(name: str, admin: bool, data_dir: Path | None, store_url: str | None) -> None:
    """Make the key NAME; its secret is printed once, on the last line."""
    # cli: the client's command line loads the store only for `dexlab keys`
    from worker.errors import DexlabError
    from worker.store.api_keys import hash_secret, new_secret

    _check_name(name)
    store = _open(data_dir, store_url, create=True)
    secret = new_secret()
    try:
        made = store.create_key(name, hash_secret(secret), admin)
    except DexlabError as exc:
        raise click.ClickException(_one_line(exc)) from None
    finally:
        store.close()
    if made is None:
        raise click.ClickException(
            f"a key named {name!r} exists (revoked keys keep their names: their jobs "
            "stay theirs); choose another name"
        )
    role = "admin key" if admin else "key"
    click.echo(
        f"Made the {role} {name!r}. Its secret, shown only this once "
        "(send it as 'Authorization: Bearer <secret>', or log in with it):"
    )
    click.echo(secret)


@keys.command(name="list")
@_store_options
def list_keys(data_dir: Path | None, store_url: str | None) -> None:
    """List the keys (never their secrets)."""
    from rich.console import Console
    from rich.table import Table

    # cli: the client's command line loads the store only for `dexlab keys`
    from worker.errors import DexlabError

    store = _open(data_dir, store_url)
    try:
        stored = store.api_keys()
    except DexlabError as exc:
        raise click.ClickException(_one_line(exc)) from None
    finally:
        store.close()
    if not stored:
        click.echo("No API keys: the service is open to everyone who can reach it.")
        return
    table = Table("name", "admin", "created (UTC)", "revoked (UTC)", "last used (UTC)")
    for key in stored:
        table.add_row(
            key.name,
            "yes" if key.admin else "no",
            _when(key.created),
            _when(key.revoked),
            _when(key.last_used),
        )
    Console(soft_wrap=True).print(table)


@keys.command()
@click.argument("name")
@_store_options
def revoke(name: str, data_dir: Path | None, store_url: str | None) -> None:
    """Revoke the key NAME: it and its browser sessions stop working within a second."""
    # cli: the client's command line loads the store only for `dexlab keys`
    from worker.errors import DexlabError

    store = _open(data_dir, store_url)
    try:
        revoked = store.revoke_key(name)
    except DexlabError as exc:
        raise click.ClickException(_one_line(exc)) from None
    finally:
        store.close()
    if revoked is None:
        raise click.ClickException(f"no key named {name!r}")
    click.echo(f"Revoked the key {name!r}; its jobs stay in the store (an admin sees them).")


def register(group: click.Group) -> None:
    """Add ``dexlab keys`` to the ``dexlab`` command."""
    group.add_command(keys)
