"""The job store is a narrow port with its connector declared once.

- The port (:mod:`worker.store.base`) is a set of role protocols; :class:`JobStore` is
  all of them and nothing more.  Each public method of the SQL store belongs to exactly
  one role, and every store method that ``service/``, ``worker/`` or ``dexlab/`` calls
  is in a role; none of them calls a private store method.
- The connection helpers and dialect hooks are written in
  :mod:`worker.store.connector`, overridden only by the dialects: no topic module of
  ``worker/store/`` restates them, and none keeps a ``TYPE_CHECKING`` block of method
  stubs (what one topic offers another is declared once, in the connector).
"""

from __future__ import annotations

import ast
import inspect
from abc import ABC
from pathlib import Path
from typing import Protocol

from worker.store.base import JobStore
from worker.store.connector import SqlConnector
from worker.store.postgres import PostgresJobStore
from worker.store.sql import SqlJobStore
from worker.store.sqlite import SqliteJobStore

ROOT = Path(__file__).resolve().parents[1]
STORE = ROOT / "worker/store"
#: The modules that may define the connection helpers: the connector declares them,
#: the dialects override the hooks.
CONNECTOR = STORE / "connector.py"
DIALECTS = {STORE / "sqlite.py", STORE / "postgres.py"}
#: What a store must offer to be retried (:class:`worker.store.retry.FaultClassifier`,
#: which the connector satisfies): a contract, not a topic.
RETRY = STORE / "retry.py"
#: The helpers every topic uses; a topic module defining one of these restates it.
HELPERS = frozenset(
    {
        "_conn",
        "_write",
        "_batch",
        "_sql",
        "_exec",
        "_one",
        "_all",
        "_job_row",
        "_lock_schema",
        "_lock_submissions",
        "classify",
        "after_fault",
        "location",
        "lock_clause",
        "retry_s",
        "ddl_types",
        "outage",
    }
)
#: The names under which code holds a store (``store.x``, ``self.store.x``, ...).
STORE_HOLDERS = frozenset({"store", "_store", "job_store", "jobs_store"})


def roles() -> list[type]:
    return [base for base in JobStore.__bases__ if base is not Protocol]


def members(cls: type) -> set[str]:
    """The public names a class defines itself (not inherited)."""
    return {name for name in vars(cls) if not name.startswith("_")}


def topic_modules() -> list[Path]:
    return sorted(set(STORE.glob("*.py")) - {CONNECTOR, RETRY} - DIALECTS)


def class_level_names(tree: ast.Module) -> set[str]:
    """Names a class body defines: methods and annotated or assigned attributes,
    including those inside an ``if`` (``if TYPE_CHECKING:``) in the class body."""
    found: set[str] = set()
    for cls in (n for n in ast.walk(tree) if isinstance(n, ast.ClassDef)):
        body = list(cls.body)
        while body:
            node = body.pop()
            if isinstance(node, ast.If):
                body.extend(node.body + node.orelse)
            elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                found.add(node.name)
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                found.add(node.target.id)
            elif isinstance(node, ast.Assign):
                found.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return found


def test_no_topic_module_restates_the_connection_helpers() -> None:
    restated = {
        path.name: sorted(HELPERS & class_level_names(ast.parse(path.read_text())))
        for path in topic_modules()
    }
    assert {name: found for name, found in restated.items() if found} == {}


def test_no_topic_module_keeps_method_stubs_for_the_type_checker() -> None:
    stubbed = []
    for path in topic_modules():
        for cls in (
            n for n in ast.walk(ast.parse(path.read_text())) if isinstance(n, ast.ClassDef)
        ):
            for node in cls.body:
                if isinstance(node, ast.If) and any(
                    isinstance(inner, ast.FunctionDef) for inner in node.body
                ):
                    stubbed.append(f"{path.name}:{node.lineno}")
    assert stubbed == []


def test_the_implementation_imports_values_not_the_port() -> None:
    """The port describes the store; the store's modules build on the values
    (:mod:`worker.store.records`) and the connector, never on the port itself."""
    importers = []
    for path in sorted(set(STORE.glob("*.py")) - {STORE / "__init__.py", STORE / "base.py"}):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module == "worker.store.base":
                importers.append(path.name)
    assert importers == []


def test_the_helpers_are_declared_in_the_connector() -> None:
    declared = class_level_names(ast.parse(CONNECTOR.read_text()))
    assert declared >= HELPERS, sorted(HELPERS - declared)


def test_every_topic_is_built_on_the_connector() -> None:
    topics = [base for base in SqlJobStore.__mro__[1:] if base not in (SqlConnector, ABC, object)]
    assert topics, "SqlJobStore has no topic classes"
    assert [t.__name__ for t in topics if not issubclass(t, SqlConnector)] == []


def test_each_public_store_method_is_in_exactly_one_role() -> None:
    owners: dict[str, list[str]] = {}
    for role in roles():
        for name in members(role):
            owners.setdefault(name, []).append(role.__name__)
    assert {n: o for n, o in owners.items() if len(o) > 1} == {}
    for dialect in (SqliteJobStore, PostgresJobStore):
        offered = {
            name
            for name, value in inspect.getmembers(dialect)
            if not name.startswith("_") and callable(value)
        }
        # Beyond the port, a store offers its machinery: the retry hooks, the URL.
        assert offered - set(owners) <= {"classify", "after_fault", "from_url"}, dialect
        assert set(owners) - offered == set(), dialect
    assert members(JobStore) == set(), "JobStore adds nothing to its roles"


def test_the_port_docstring_lists_each_role_as_it_is() -> None:
    import worker.store.base as port

    listed: dict[str, set[str]] = {}
    text = " ".join((port.__doc__ or "").split())
    for item in text.split("- :class:`")[1:]:
        role, _, rest = item.partition("`: ")
        methods = rest.split(".")[0].replace("(quotas: :class:`QueueLimits`)", "")
        listed[role] = {m.strip() for m in methods.split(",")}
    assert listed == {role.__name__: members(role) for role in roles()}


def store_calls(path: Path) -> set[str]:
    """The attributes read off a store holder in ``path`` (``store.get_job``,
    ``self._store.complete``, ``request.app.state.store.ping``)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if not isinstance(node, ast.Attribute):
            continue
        holder = node.value
        name = (
            holder.id
            if isinstance(holder, ast.Name)
            else holder.attr
            if isinstance(holder, ast.Attribute)
            else None
        )
        if name in STORE_HOLDERS:
            found.add(node.attr)
    return found


def test_the_roles_cover_every_store_method_the_tree_calls() -> None:
    port = set().union(*(members(role) for role in roles()))
    callers = [
        p
        for folder in ("service", "worker", "dexlab")
        for p in (ROOT / folder).rglob("*.py")
        if STORE not in p.parents
    ]
    called = {(p.relative_to(ROOT).as_posix(), a) for p in callers for a in store_calls(p)}
    public = {(where, a) for where, a in called if not a.startswith("_")}
    assert len({a for _, a in public}) >= 30, "the scan found too few store calls to trust"
    assert sorted((where, a) for where, a in public if a not in port) == []
    # Nobody outside the store reaches behind the port (a connection, a statement).
    assert sorted((where, a) for where, a in called if a.startswith("_")) == []


def test_the_call_scan_sees_a_call_outside_the_port(tmp_path: Path) -> None:
    sample = tmp_path / "caller.py"
    sample.write_text("def f(app):\n    app.state.store.get_job('x')\n    store.vacuum()\n")
    assert store_calls(sample) == {"get_job", "vacuum"}
