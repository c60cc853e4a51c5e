"""Nothing reads the environment after start-up: only the entry points build the settings
tree (``service.config.Settings``, the one ``BaseSettings``) and pass it down, and only
the modules listed here read ``os.environ``, each for a reason of its own.

Counted in ``service``, ``worker`` and ``dexlab`` (the test deployments build the tree
too, as entry points of their own).
"""

from __future__ import annotations

import ast
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("service", "worker", "dexlab")

#: Where the settings tree is built: the entry points, and how many times each.
SETTINGS_BUILT = {
    "service.cli": 2,  # `dexlab serve` and `dexlab worker`
    "dexlab.cli.keys": 1,  # `dexlab keys`: the store the server's settings name
}
#: Who reads the environment itself, and how many times.
ENVIRONMENT_READS = {
    "dexlab.connection": 2,  # the Python client's own DEXLAB_URL and DEXLAB_API_KEY
    "dexlab.cli.render": 1,  # COLUMNS: how wide the terminal's tables are
}
#: The one class that reads ``DEXLAB_*``.
SETTINGS_CLASS = ("service.config", "Settings")
_OS_READERS = {"environ", "environb", "getenv", "getenvb"}


def modules() -> dict[str, ast.Module]:
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            found[".".join(parts)] = ast.parse(path.read_text(), filename=str(path))
    return found


def base_names(node: ast.ClassDef) -> set[str]:
    return {b.id if isinstance(b, ast.Name) else ast.unparse(b).split(".")[-1]
            for b in node.bases}  # fmt: skip


def settings_classes(tree: dict[str, ast.Module]) -> set[tuple[str, str]]:
    """(module, class) of every class deriving, here or through another class of the
    packages, from pydantic-settings' ``BaseSettings`` (which reads the environment)."""
    classes = [(module, node) for module, body in tree.items() for node in ast.walk(body)
               if isinstance(node, ast.ClassDef)]  # fmt: skip
    derived: set[str] = {"BaseSettings"}
    while True:
        more = {node.name for _, node in classes if base_names(node) & derived} - derived
        if not more:
            return {(module, node.name) for module, node in classes if node.name in derived}
        derived |= more


def constructions(body: ast.Module, names: set[str]) -> int:
    """Calls of a class named in ``names`` (``Settings(...)``, ``config.Settings(...)``)."""
    count = 0
    for node in ast.walk(body):
        if isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else getattr(func, "attr", None)
            count += name in names
    return count


def environment_reads(body: ast.Module) -> int:
    """``os.environ`` / ``os.getenv`` uses, and names imported from ``os`` that read it."""
    count = 0
    for node in ast.walk(body):
        if isinstance(node, ast.Attribute) and node.attr in _OS_READERS:
            count += isinstance(node.value, ast.Name) and node.value.id == "os"
        elif isinstance(node, ast.ImportFrom) and node.module == "os":
            count += sum(alias.name in _OS_READERS for alias in node.names)
    return count


def test_one_class_reads_the_settings() -> None:
    assert settings_classes(modules()) == {SETTINGS_CLASS}


def test_only_the_entry_points_build_the_settings() -> None:
    tree = modules()
    names = {name for _, name in settings_classes(tree)}
    built = Counter({module: constructions(body, names) for module, body in tree.items()})
    assert +built == SETTINGS_BUILT


def test_only_the_listed_modules_read_the_environment() -> None:
    tree = modules()
    reads = Counter({module: environment_reads(body) for module, body in tree.items()})
    assert +reads == ENVIRONMENT_READS


def test_the_counters_see_what_they_count() -> None:
    """The counters find each form of a read (so a zero above means none)."""
    source = ast.parse(
        "import os\nfrom os import environ, getenv\n"
        "os.environ.get('A'); os.getenv('B'); environ['C']\n"
        "Settings(); config.Settings(port=1); Other()\n"
        "class Mine(BaseSettings): pass\nclass Child(Mine): pass\n"
    )
    assert environment_reads(source) == 4
    assert constructions(source, {"Settings"}) == 2
    assert settings_classes({"m": source}) == {("m", "Mine"), ("m", "Child")}
