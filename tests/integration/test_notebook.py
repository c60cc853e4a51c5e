"""examples/notebook.ipynb runs from top to bottom against a real service (embedded),
through the Python client, and redraws one figure from each paper."""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

from tests.integration.servers import deployment

pytestmark = pytest.mark.integration

NOTEBOOK = Path(__file__).resolve().parents[2] / "examples" / "notebook.ipynb"


def outputs(notebook: nbformat.NotebookNode, kind: str) -> list[str]:
    """Every output of the given MIME type (or stream text for "stream")."""
    found = []
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            if kind == "stream" and output.output_type == "stream":
                found.append(output.text)
            elif kind in output.get("data", {}):
                found.append(output.data[kind])
    return found


def test_the_notebook_is_committed_without_outputs() -> None:
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(notebook)
    code = [c for c in notebook.cells if c.cell_type == "code"]
    assert code and all(not c.outputs and c.execution_count is None for c in code)


def test_the_notebook_runs_against_a_real_service(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    with deployment("embedded", tmp_path / "service", workers=2) as service:
        monkeypatch.setenv("DEXLAB_URL", service.base_url)  # the kernel inherits it
        monkeypatch.delenv("DEXLAB_API_KEY", raising=False)
        monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
        NotebookClient(
            notebook, timeout=120, kernel_name="python3",
            resources={"metadata": {"path": str(tmp_path)}},
        ).execute()  # fmt: skip
        jobs = service.client.get("/v1/jobs").json()["jobs"]
    # One job per paper, each successful; one figure drawn from each.
    assert {j["processID"] for j in jobs} == {
        "planar3r-dexterity-map", "planar2dof-conditioning-map", "spm-conditioning-map",
        "chain-parallelism",
    }  # fmt: skip
    assert all(j["status"] == "successful" for j in jobs)
    assert len(outputs(notebook, "image/png")) == 4
    html = outputs(notebook, "text/html")
    # The progress display, updated in place to the end, and a job shown inline.
    assert sum('<progress max="100" value="100"' in h for h in html) == 4
    assert any('class="dexlab-job"' in h and "data:image/png;base64," in h for h in html)
    assert "inputs.lengths" in "".join(outputs(notebook, "stream"))
