"""The import graph: no cycle through the worker, and few imports hidden in functions.

An import placed inside a function hides a dependency from the reader and can hold an
import cycle open (``worker/processes.py`` once imported the families inside a function
while they imported it at the top, and the design study rebuilt the registry inside
five functions).  A function-local import of a project module is allowed for three
reasons only, each written on the line above it as ``# <kind>: <why>``:

- ``lazy``: a module loaded when a job, a study or a validation needs it, so that the
  registry (and the API that lists it) never loads scipy or matplotlib;
- ``optional``: a module wrapping an optional dependency (Celery, PostgreSQL), loaded
  only when the deployment uses it;
- ``cli``: a command line loading what one command needs when it runs.

The graph checked for cycles holds every module-level import, every lazy one and every
optional one: the dependencies a module has whenever it (or the backend it chooses) is
used.  Command lines load what one command needs, so their imports are left out of it.
"""

from __future__ import annotations

import ast
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("service", "worker", "dexlab")
KINDS = ("lazy", "optional", "cli")
#: The most function-local imports of project modules, by kind (lower them, never
#: raise them without a reason the module docstring accepts).
BUDGET = {"lazy": 26, "optional": 3, "cli": 18}  # lazy: each job module (+ the previews)
#: The command lines (where ``cli`` imports may be).
CLI_MODULES = ("service.cli", "dexlab.cli")


@dataclass(frozen=True)
class Import:
    """One import statement of a project module: where, what, and in which kind."""

    module: str
    line: int
    targets: tuple[str, ...]
    local: bool
    #: The kind its comment gives (local imports only); "" for none.
    kind: str = ""


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {
    module_name(p): p for package in PACKAGES for p in sorted((ROOT / package).rglob("*.py"))
}


def _resolve(module: str, name: str | None) -> str | None:
    """The project module an import loads: ``from a.b import c`` is ``a.b.c`` if that is
    a module, else ``a.b`` (or its nearest package)."""
    if name is not None and f"{module}.{name}" in MODULES:
        return f"{module}.{name}"
    parts = module.split(".")
    while parts and ".".join(parts) not in MODULES:
        parts.pop()
    return ".".join(parts) or None


def _targets(node: ast.Import | ast.ImportFrom) -> tuple[str, ...]:
    if isinstance(node, ast.Import):
        pairs = [(alias.name, None) for alias in node.names]
    else:
        pairs = [(node.module or "", alias.name) for alias in node.names]
    found = {_resolve(m, n) for m, n in pairs if m.split(".")[0] in PACKAGES}
    return tuple(sorted(t for t in found if t is not None))


def _kind(lines: list[str], first: ast.stmt) -> str:
    above = lines[first.lineno - 2].strip() if first.lineno >= 2 else ""
    kind, colon, why = above.removeprefix("#").strip().partition(":")
    return kind if above.startswith("#") and colon and why.strip() else ""


def imports_of(module: str) -> list[Import]:
    """Every import of a project module in ``module``: at module level (outside
    ``if TYPE_CHECKING``), or inside a function with the kind its group's comment gives
    (consecutive imports share the comment above the first)."""
    text = MODULES[module].read_text()
    lines = text.splitlines()
    tree = ast.parse(text)
    functions = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef)]
    local_nodes: dict[int, str] = {}
    for function in functions:
        for node in ast.walk(function):
            for field in ("body", "orelse", "finalbody"):
                body = getattr(node, field, None)
                if not isinstance(body, list):
                    continue
                kind = ""
                previous = False
                for statement in body:
                    is_import = isinstance(statement, ast.Import | ast.ImportFrom) and bool(
                        _targets(statement)
                    )
                    if is_import and not previous:
                        kind = _kind(lines, statement)
                    if is_import:
                        local_nodes[id(statement)] = kind
                    previous = is_import
    type_checking = {
        id(inner)
        for node in ast.walk(tree)
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
        for inner in ast.walk(node)
    }
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Import | ast.ImportFrom) or id(node) in type_checking:
            continue
        targets = _targets(node)
        if not targets:
            continue
        local = id(node) in local_nodes
        found.append(Import(module, node.lineno, targets, local, local_nodes.get(id(node), "")))
    return found


IMPORTS = [i for module in MODULES for i in imports_of(module)]
LOCAL = [i for i in IMPORTS if i.local]


def where(i: Import) -> str:
    return f"{MODULES[i.module].relative_to(ROOT)}:{i.line}"


def test_every_function_local_import_gives_its_reason() -> None:
    unexplained = [where(i) for i in LOCAL if i.kind not in KINDS]
    assert not unexplained, (
        "a function-local import of a project module needs '# lazy: ...', "
        f"'# optional: ...' or '# cli: ...' on the line above it: {unexplained}"
    )


def test_command_line_imports_are_in_the_command_lines() -> None:
    elsewhere = [
        where(i)
        for i in LOCAL
        if i.kind == "cli" and not any(i.module.startswith(c) for c in CLI_MODULES)
    ]
    assert not elsewhere, f"'cli' imports outside the command lines: {elsewhere}"


def test_function_local_imports_stay_within_their_budget() -> None:
    counts = Counter(i.kind for i in LOCAL)
    over = {kind: n for kind, n in counts.items() if n > BUDGET.get(kind, 0)}
    assert not over, f"function-local imports by kind {dict(counts)}, budget {BUDGET}"


def import_graph() -> dict[str, set[str]]:
    """Module -> the project modules it imports whenever it is used (module level, lazy
    and optional; not the command lines' imports, each made for one command)."""
    graph: dict[str, set[str]] = {module: set() for module in MODULES}
    for i in IMPORTS:
        if not i.local or i.kind != "cli":
            graph[i.module].update(t for t in i.targets if t != i.module)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_import_cycle_through_the_worker() -> None:
    """No cycle through a family, the contract, the registry or the runtime: the
    registry imports the families, which import the contract, which imports neither."""
    through_worker = [c for c in cycles(import_graph()) if any(m.startswith("worker") for m in c)]
    assert not through_worker, f"import cycles: {through_worker}"


def test_the_contract_imports_no_family_and_no_registry() -> None:
    """``worker.processes`` (what a process is) and the job contract stand below the
    families: importing them loads no family, no study and no registry."""
    graph = import_graph()
    for contract in ("worker.processes", "worker.contract"):
        seen, todo = set(), [contract]
        while todo:
            module = todo.pop()
            if module not in seen:
                seen.add(module)
                todo.extend(graph[module])
        below = {m for m in seen if m.startswith(("worker.families", "worker.studies"))}
        assert not below and "worker.registry" not in seen, (contract, below)


def test_the_study_never_builds_a_registry() -> None:
    """The design study gets the registry it studies; it never builds one."""
    builders = {"worker.registry", "default_registry", "worker_registry"}
    offenders = [
        f"{module_name(path)}:{node.lineno}"
        for path in sorted((ROOT / "worker/studies").rglob("*.py"))
        for node in ast.walk(ast.parse(path.read_text()))
        if isinstance(node, ast.Import | ast.ImportFrom)
        and ({getattr(node, "module", None)} | {a.name for a in node.names}) & builders
    ]
    assert not offenders, offenders
