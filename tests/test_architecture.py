"""Imports go one way, and the tree keeps its shape.

``service`` (HTTP) -> the job runtime (``worker/*.py``, ``store/``, ``dispatch/``) ->
``worker/families/<family>/`` (the science) -> ``worker/common/`` (what families share).
``worker/studies/`` (``design-study``) is a process built on the others: like a family
it may use ``worker.common``, and it reaches the families only through the registry.
The runtime reaches a family only through the registry (:mod:`worker.registry`); a
family's ``kinematics/`` is pure numpy/scipy; families never import each other; figures
never use pyplot; modules stay under 400 lines and a folder with three modules named
``<word>_*`` is a package waiting to happen.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FAMILIES = sorted(p.parent.name for p in (ROOT / "worker/families").glob("*/__init__.py"))
#: The pure modules of ``worker.common`` (a family's kinematics may import these only).
PURE_COMMON = {"worker.common.arrays", "worker.common.grashof", "worker.common.parameter_errors"}
#: The job runtime: every ``worker`` module outside ``families/``, ``common/``, ``studies/``.
RUNTIME = sorted(
    p
    for p in (ROOT / "worker").rglob("*.py")
    if not {"families", "common", "studies"} & set(p.relative_to(ROOT / "worker").parts)
)
MAX_LINES = 400


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imports_of(path: Path) -> set[tuple[str, str | None]]:
    """(module, name) of every import; ``name`` is None for ``import m``."""
    tree = ast.parse(path.read_text(), filename=str(path))
    found: set[tuple[str, str | None]] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update((alias.name, None) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            assert node.level == 0, f"{path}: relative import (use the absolute module path)"
            assert node.module is not None
            found.update((node.module, alias.name) for alias in node.names)
    return found


def imported_modules(path: Path) -> set[str]:
    """Every module an import may load: ``from a.b import c`` counts ``a.b`` and
    ``a.b.c`` (``c`` may be a submodule)."""
    names: set[str] = set()
    for module, name in imports_of(path):
        names.add(module)
        if name is not None:
            names.add(f"{module}.{name}")
    return names


def under(module: str, *prefixes: str) -> bool:
    return any(module == p or module.startswith(p + ".") for p in prefixes)


def python_files(package: str) -> list[Path]:
    return sorted((ROOT / package).rglob("*.py"))


def family_of(module: str) -> str | None:
    parts = module.split(".")
    return parts[2] if parts[:2] == ["worker", "families"] and len(parts) > 2 else None


def rel(p: Path) -> str:
    return str(p.relative_to(ROOT))


def test_every_family_folder_is_a_package_with_kinematics() -> None:
    assert FAMILIES == [
        "chains", "planar_parallel", "planar_serial", "serial", "spherical_parallel"
    ]  # fmt: skip
    for family in FAMILIES:
        assert (ROOT / "worker/families" / family / "kinematics/__init__.py").is_file(), family


@pytest.mark.parametrize("path", python_files("worker"), ids=rel)
def test_worker_never_imports_service(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if under(m, "service", "dexlab")}
    assert not offenders, f"{path} imports the HTTP layer or the client: {offenders}"


@pytest.mark.parametrize("path", RUNTIME, ids=rel)
def test_the_runtime_knows_no_family(path: Path) -> None:
    """The runtime reaches families only through the registry in ``registry.py``."""
    offenders = {m for m in imported_modules(path) if under(m, "worker.families", "worker.common")}
    if path == ROOT / "worker/registry.py":
        offenders -= {"worker.families", *(f"worker.families.{f}" for f in FAMILIES)}
    assert not offenders, f"{path} imports family code: {offenders}"


@pytest.mark.parametrize("path", python_files("worker/studies"), ids=rel)
def test_studies_reach_families_only_through_the_registry(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if under(m, "worker.families")}
    assert not offenders, f"{path} imports family code: {offenders}"


def test_the_registry_lists_every_family_folder() -> None:
    """A new folder under ``worker/families/`` without its line in the registry fails."""
    listed = {
        name
        for module, name in imports_of(ROOT / "worker/registry.py")
        if module == "worker.families"
    }
    assert sorted(n for n in listed if n is not None) == FAMILIES


def test_loading_the_registry_loads_no_numerics_beyond_numpy() -> None:
    code = (
        "import sys; from worker.registry import worker_registry; worker_registry(); "
        "print(sorted(m for m in ('scipy', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


@pytest.mark.parametrize("path", python_files("worker/families"), ids=rel)
def test_families_never_import_each_other(path: Path) -> None:
    own = family_of(module_name(path))
    offenders = {m for m in imported_modules(path) if family_of(m) not in (None, own)}
    assert not offenders, f"{path} imports another family: {offenders}"


KINEMATICS_FORBIDDEN = (
    "worker", "service", "dexlab", "pydantic", "fastapi", "matplotlib", "sqlite3", "os",
    "pathlib", "io", "json", "logging", "socket", "subprocess",
)  # fmt: skip
KINEMATICS_FILES = [
    *(p for f in FAMILIES for p in python_files(f"worker/families/{f}/kinematics")),
    *(ROOT / (m.replace(".", "/") + ".py") for m in sorted(PURE_COMMON)),
]


@pytest.mark.parametrize("path", KINEMATICS_FILES, ids=rel)
def test_kinematics_is_pure(path: Path) -> None:
    """numpy/scipy only: no I/O, no pydantic, no matplotlib, no runtime; within dexlab,
    the family's own kinematics and the pure modules of ``worker.common``."""
    own = module_name(path)
    package = f"worker.families.{family_of(own)}.kinematics" if family_of(own) else None
    offenders = set()
    for module in imported_modules(path):
        if package is not None and under(module, package):
            continue
        if under(module, *PURE_COMMON) or module == "worker.common":
            continue
        if under(module, *KINEMATICS_FORBIDDEN):
            offenders.add(module)
    assert not offenders, f"{path} must stay pure numpy/scipy, but imports {offenders}"
    assert "open(" not in path.read_text(), f"{path} does I/O"
    if package is not None and own != package:  # siblings by module path, not the front
        folder = path.parent
        through_front = {
            f"{module}.{name}"
            for module, name in imports_of(path)
            if module == package and not (name and (folder / f"{name}.py").is_file())
        }
        assert not through_front, (
            f"{path} imports names through its package's front: {through_front}"
        )


@pytest.mark.parametrize(
    "path",
    [*(p for f in FAMILIES for p in python_files(f"worker/families/{f}/plots")),
     ROOT / "worker/common/figures.py"],
    ids=rel,
)  # fmt: skip
def test_plots_never_use_pyplot(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if under(m, "matplotlib.pyplot")}
    assert not offenders, f"{path} uses pyplot"


@pytest.mark.parametrize("path", python_files("worker/common"), ids=rel)
def test_common_imports_no_family(path: Path) -> None:
    offenders = {m for m in imported_modules(path) if under(m, "worker.families", "worker.studies")}
    assert not offenders, f"{path} imports a family: {offenders}"


@pytest.mark.parametrize("path", python_files("service"), ids=rel)
def test_service_has_no_numerics_sql_or_family(path: Path) -> None:
    offenders = {
        m
        for m in imported_modules(path)
        if m.split(".")[0] in {"numpy", "scipy", "matplotlib", "sqlite3"}
        or under(m, "worker.families", "worker.common")
    }
    assert not offenders, f"{path} does numerics, SQL or science in the HTTP layer: {offenders}"


def product_modules() -> list[Path]:
    return [p for pkg in ("service", "worker", "dexlab") for p in python_files(pkg)]


def test_no_module_passes_400_lines() -> None:
    long = {
        rel(p): n for p in product_modules() if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert not long, f"modules over {MAX_LINES} lines (split them by noun): {long}"


def test_no_folder_holds_three_modules_with_one_prefix() -> None:
    crowded = {}
    for folder in {p.parent for p in product_modules()}:
        stems = [p.stem for p in folder.glob("*.py") if "_" in p.stem.strip("_")]
        prefixes = Counter(stem.split("_")[0] for stem in stems)
        many = {prefix: n for prefix, n in prefixes.items() if n >= 3}
        if many:
            crowded[rel(folder)] = many
    assert not crowded, f"a shared prefix is a package waiting to happen: {crowded}"


def test_no_utils_module() -> None:
    banned = {"utils.py", "helpers.py", "misc.py"}
    assert not [p for p in product_modules() if p.name in banned]
