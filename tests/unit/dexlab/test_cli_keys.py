"""``dexlab keys``: the secret once on the last line, never listed; errors as one line."""

from __future__ import annotations

from pathlib import Path

import pytest

from dexlab.cli import main
from worker.store import open_store
from worker.store.api_keys import hash_secret


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as exit_info:
        main(list(args))
    out, err = capsys.readouterr()
    code = exit_info.value.code
    return (code if isinstance(code, int) else 1), out, err


def test_create_list_revoke(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = str(tmp_path)
    code, out, _ = run(capsys, "keys", "create", "alice", "--admin", "--data-dir", data)
    assert code == 0
    secret = out.strip().splitlines()[-1]
    assert secret.startswith("dxk_") and out.count(secret) == 1
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    try:
        (key,) = store.api_keys()
        assert key.name == "alice" and key.admin and key.secret_hash == hash_secret(secret)
    finally:
        store.close()
    assert secret.encode() not in (tmp_path / "jobs.db").read_bytes()

    code, out, _ = run(capsys, "keys", "list", "--data-dir", data)
    assert code == 0 and "alice" in out and "yes" in out
    assert secret not in out and hash_secret(secret) not in out

    code, out, _ = run(capsys, "keys", "revoke", "alice", "--data-dir", data)
    assert code == 0 and "Revoked" in out
    code, out, _ = run(capsys, "keys", "list", "--data-dir", data)
    assert "UTC" in out and out.count("—") == 1  # revoked: a time; never used: a dash


@pytest.mark.parametrize(
    ("args", "code", "phrase"),
    [
        (["keys", "create", "bad name"], 2, "The key name must be"),
        (["keys", "create", "alice", "--store-url", "sqlite:///x.db"], 2, "not both"),
        (["keys", "create", "taken"], 1, "a key named 'taken' exists"),
        (["keys", "revoke", "nobody"], 1, "no key named 'nobody'"),
    ],
)
def test_errors_are_one_line(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    args: list[str],
    code: int,
    phrase: str,
) -> None:
    run(capsys, "keys", "create", "taken", "--data-dir", str(tmp_path))
    got, _, err = run(capsys, *args, "--data-dir", str(tmp_path))
    lines = err.strip().splitlines()
    assert got == code and len(lines) == 1 and phrase in lines[0], err


def test_list_without_a_store_says_so(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "keys", "list", "--data-dir", str(tmp_path / "none"))
    assert code == 1 and "no job store at" in err
    assert not (tmp_path / "none").exists()
