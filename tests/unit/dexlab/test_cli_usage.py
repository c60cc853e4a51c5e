"""The ``dexlab`` command's own behaviour: version, usage errors as one line, exit codes,
and that the client side imports neither the server nor the worker."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from dexlab.cli import main


def run(*args: str) -> subprocess.CompletedProcess[str]:
    script = Path(sys.executable).parent / "dexlab"
    command = [str(script)] if script.exists() else [sys.executable, "-m", "service"]
    return subprocess.run([*command, *args], capture_output=True, text=True, timeout=60)


def test_version_prints_the_installed_version() -> None:
    done = run("--version")
    assert done.returncode == 0
    assert done.stdout.startswith("dexlab ") and done.stdout.strip() != "dexlab"


@pytest.mark.parametrize(
    ("args", "phrase"),
    [
        (["serve", "--bogus"], "No such option '--bogus'"),
        (["serve", "--port", "abc"], "'--port'"),
        (["worker", "--workers", "-1"], "'--workers'"),
        (["nosuchcommand"], "No such command"),
    ],
)
def test_a_usage_error_exits_2_with_one_line_and_no_traceback(args: list[str], phrase: str) -> None:
    done = run(*args)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("dexlab: ") and phrase in lines[0]
    assert "Traceback" not in done.stderr + done.stdout


def test_no_command_shows_the_help_and_exits_2() -> None:
    done = run()
    assert done.returncode == 2
    assert "serve" in done.stderr and "worker" in done.stderr


def test_worker_without_processes_is_refused_with_exit_2() -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["worker", "--workers", "0"])
    assert exit_info.value.code == 2


def test_importing_the_command_line_loads_neither_server_nor_worker() -> None:
    code = (
        "import sys, dexlab, dexlab.cli; "
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('service', 'worker')))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.strip() == "[]"


def test_a_bad_setting_exits_2_naming_it_without_its_value() -> None:
    script = Path(sys.executable).parent / "dexlab"
    command = [str(script)] if script.exists() else [sys.executable, "-m", "service"]
    env = {**__import__("os").environ, "DEXLAB_API_KEYS": "s3cretvalue-with-no-name"}
    done = subprocess.run(
        [*command, "serve", "--port", "0"], capture_output=True, text=True, env=env, timeout=60
    )
    assert done.returncode == 2
    assert "DEXLAB_API_KEYS" in done.stderr and "s3cretvalue" not in done.stderr
    assert "Traceback" not in done.stderr
