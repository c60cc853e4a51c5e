"""Imports go one way: service -> worker -> worker.kinematics (pure numpy/scipy)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def imported_modules(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), filename=str(path))
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
    return names


def python_files(package: str) -> list[Path]:
    return sorted((ROOT / package).rglob("*.py"))


@pytest.mark.parametrize("path", python_files("worker"), ids=lambda p: str(p.relative_to(ROOT)))
def test_worker_never_imports_service(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if m == "service" or m.startswith("service.")}
    assert not offenders, f"{path} imports the HTTP layer: {offenders}"


KINEMATICS_FORBIDDEN = (
    "worker.contract", "worker.store", "worker.jobs", "worker.plotting", "worker.runner",
    "worker.pool", "worker.processes", "service", "pydantic", "fastapi", "matplotlib",
    "sqlite3", "os", "pathlib", "io", "json", "logging", "socket", "subprocess",
)


@pytest.mark.parametrize(
    "path", python_files("worker/kinematics"), ids=lambda p: str(p.relative_to(ROOT))
)
def test_kinematics_is_pure(path: Path) -> None:
    offenders = {
        m for m in imported_modules(path)
        if any(m == f or m.startswith(f + ".") for f in KINEMATICS_FORBIDDEN)
    }
    assert not offenders, f"{path} must stay pure numpy/scipy, but imports {offenders}"
    assert "open(" not in path.read_text(), f"{path} does I/O"


@pytest.mark.parametrize(
    "path", python_files("worker/plotting"), ids=lambda p: str(p.relative_to(ROOT))
)
def test_plotting_never_uses_pyplot(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if m.startswith("matplotlib.pyplot")}
    assert not offenders, f"{path} uses pyplot"


@pytest.mark.parametrize("path", python_files("service"), ids=lambda p: str(p.relative_to(ROOT)))
def test_service_has_no_numerics_or_sql(path: Path) -> None:
    offenders = {
        m for m in imported_modules(path)
        if m.split(".")[0] in {"numpy", "scipy", "matplotlib", "sqlite3"}
        or m.startswith("worker.kinematics")
    }
    assert not offenders, f"{path} does numerics or SQL in the HTTP layer: {offenders}"


def test_no_utils_module() -> None:
    assert not [p for p in ROOT.glob("*/**/utils.py") if ".venv" not in p.parts]
