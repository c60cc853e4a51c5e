"""examples/notebook.ipynb runs from top to bottom against a real service (embedded),
through the Python client, and redraws one figure from each paper; those figures pass
the figure check, mask what cannot be reached and outline W_kappa0 where it ends
(tests/integration/notebook_figures.py records them from inside the kernel)."""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import contourpy
import nbformat
import numpy as np
import pytest
from nbclient import NotebookClient
from scipy.spatial import cKDTree

from tests.integration.servers import deployment

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOK = ROOT / "examples" / "notebook.ipynb"
#: Run before the notebook's cells: plt.show() records each figure first.
RECORDER = (
    f"import sys\nsys.path.insert(0, {str(ROOT)!r})\n"
    "from tests.integration.notebook_figures import record_figures\n"
    "record_figures('figures.jsonl')"
)


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
    notebook.cells.insert(0, nbformat.v4.new_code_cell(RECORDER))
    with deployment("embedded", tmp_path / "service", workers=2) as service:
        monkeypatch.setenv("DEXLAB_URL", service.base_url)  # the kernel inherits it
        monkeypatch.delenv("DEXLAB_API_KEY", raising=False)
        monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
        NotebookClient(
            notebook, timeout=120, kernel_name="python3",
            resources={"metadata": {"path": str(tmp_path)}},
        ).execute()  # fmt: skip
        jobs = service.client.get("/v1/jobs").json()["jobs"]
        parallel = next(j for j in jobs if j["processID"] == "planar2dof-conditioning-map")
        npz = service.client.get(f"/v1/jobs/{parallel['jobID']}/results/conditioning_map.npz")
        arm = next(j for j in jobs if j["processID"] == "planar3r-dexterity-map")
        dexterity = service.client.get(f"/v1/jobs/{arm['jobID']}/results/dexterity_map.npz")
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
    figures = [json.loads(line) for line in (tmp_path / "figures.jsonl").read_text().splitlines()]
    assert len(figures) == 4
    # Units on every axis, mathtext symbols, no clipped or overlapping text, contour
    # lines broken only under their labels.
    assert {f["title"]: f["defects"] for f in figures if f["defects"]} == {}
    # The arm's unreachable nodes (d_z = 0) are masked, not drawn as a value.
    with np.load(io.BytesIO(dexterity.content)) as arrays:
        reachable = int(np.sum(arrays["d_z"] > 0.0))
    assert [f["finite_cells"] for f in figures if "Patel" in f["title"]] == [reachable]
    with np.load(io.BytesIO(npz.content)) as maps:
        assert_outlines_w_kappa0(figures, maps)


def assert_outlines_w_kappa0(figures: list[dict[str, Any]], maps: Any) -> None:
    """What the notebook labels W_kappa0 runs along the whole boundary of the set
    {1/kappa >= limit} (unreachable nodes outside it) and nowhere else, to within two
    grid steps: not, say, the outline of only the lowest run of each column."""
    x, y = maps["x"], maps["y"]
    field = np.nan_to_num(maps["inverse_condition"], nan=0.0)
    lines = contourpy.contour_generator(x, y, field).lines(float(maps["inverse_condition_limit"]))
    boundary = np.concatenate(lines)
    drawn = np.array([v for f in figures for v in f["w_kappa0"]], dtype=float).reshape(-1, 2)
    assert len(drawn), "no artist labelled W_kappa0"
    step = 2.0 * max(float(np.diff(x).max()), float(np.diff(y).max()))
    missed = cKDTree(drawn).query(boundary)[0] > step
    astray = cKDTree(boundary).query(drawn)[0] > step
    assert not missed.any(), f"boundary points not drawn: {boundary[missed][:5].tolist()}"
    assert not astray.any(), f"drawn off the boundary: {drawn[astray][:5].tolist()}"
