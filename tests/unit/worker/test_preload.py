"""``preload_job_modules``: after it, running a job imports nothing more (a prefork
worker calls it before forking, so a pool process's first job does not pay the
imports).  In a fresh interpreter, since this one has imported them already."""

from __future__ import annotations

import json
import subprocess
import sys

SCRIPT = """
import json, sys
from worker.registry import preload_job_modules, worker_registry

names = preload_job_modules() if sys.argv[1] == "preload" else []
before = set(sys.modules)
definition = worker_registry().get("fourbar-grashof")


class Quiet:
    def __getattr__(self, name):
        return lambda *args, **kwargs: None


inputs = definition.inputs_model.model_validate({"lengths": [2, 3, 4, 5], "ground": 0})
outcome = definition.run(inputs, Quiet())
new = sorted(m for m in set(sys.modules) - before if m.startswith("worker"))
print(json.dumps({"names": names, "new": new, "files": len(outcome.artifacts)}))
"""


def run(mode: str) -> dict[str, object]:
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT, mode],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    report: dict[str, object] = json.loads(out.stdout.strip().splitlines()[-1])
    return report


def test_after_preloading_a_job_imports_no_module_of_ours() -> None:
    report = run("preload")
    names = set(report["names"])  # type: ignore[call-overload]
    assert {
        "worker.families.chains.jobs.fourbar",
        "worker.families.spherical_parallel.jobs",
        "worker.studies.chunk",
    } <= names
    assert report["files"] != 0  # the figures were drawn, with what was preloaded
    assert report["new"] == []
    # Without it, the first job imports its modules (what the preload saves).
    assert "worker.families.chains.jobs.fourbar" in run("no")["new"]  # type: ignore[operator]
