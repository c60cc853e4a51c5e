"""The live explorers' latency in a real browser: input event to redrawn chart.

Starts its own `dexlab serve` (embedded, SQLite, a one-process pool left idle), opens
each explorer (``/pages/processes/{id}/explore``) in headless Chromium (Playwright on
the system Chromium, as the browser tests), lets it draw, warms up with ``--warmup``
slider changes, then times ``--changes`` more: from the slider's ``input`` event to the
explorer's ``explorer:drawn`` event for that change, i.e. the preview request, its
computation, the JSON and Plotly's redraw of every heat map and the indices (the
explorer waits for ``Plotly.react`` to resolve).  Changes are made one after the other
(each waits for its redraw), sweeping one design field back and forth near the start.

The explorers start where the issue sets its targets (p95 < 150 ms): the SPM
conditioning map at its first worked example's sampling (Table 1, 144 samples, three
121 x 41 maps) and the 3R dexterity map on a 101 x 101 grid under the paper's joint
limits (Example 1 Case 3, exact events); the 2-DOF conditioning map at 101 x 101.

Prints one line per explorer ending in ``p50 <x> ms p95 <y> ms``.

Usage: python bench/explorer_latency.py [--changes 60] [--warmup 10]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import percentile

from tests.browser import chromium, open_page
from tests.integration.servers import deployment

#: Explorer -> (the field swept, its values, what the start is).
SWEEPS: dict[str, tuple[str, tuple[float, ...], str]] = {
    "spm-conditioning-map": (
        "alpha1_deg", tuple(55.0 + 0.5 * i for i in range(21)),
        "Table 1 sampling: 144 samples, 3 maps of 73 x 25",
    ),
    "planar3r-dexterity-map": (
        "links.2", tuple(7.0 + 0.1 * i for i in range(21)),
        "101 x 101 grid, the paper's joint limits, exact events",
    ),
    "planar2dof-conditioning-map": (
        "l2", tuple(1.4 + 0.01 * i for i in range(21)),
        "101 x 101 grid, 1/kappa and beta_min maps",
    ),
}  # fmt: skip

#: One timed change: move the slider, resolve with the ms until its redraw.
CHANGE = """([path, value]) => new Promise((resolve) => {
  const root = document.getElementById("explorer");
  const range = document.querySelector(`input[type=range][data-path='${path}']`);
  const start = performance.now();
  const expected = String(Number(root.dataset.drawn) + 1);
  root.addEventListener("explorer:drawn", function done(event) {
    if (String(event.detail.change) !== expected) { return; }
    root.removeEventListener("explorer:drawn", done);
    resolve({ms: performance.now() - start, state: root.dataset.state});
  });
  range.value = String(value);
  range.dispatchEvent(new Event("input", {bubbles: true}));
})"""


def sweep_values(values: tuple[float, ...], count: int) -> list[float]:
    """``count`` values going back and forth over ``values`` (each a real change)."""
    cycle = list(values) + list(values[-2:0:-1])
    return [cycle[i % len(cycle)] for i in range(1, count + 1)]


def measure(page: Any, base_url: str, process_id: str, changes: int, warmup: int) -> list[float]:
    path, values, _ = SWEEPS[process_id]
    page.goto(f"{base_url}/pages/processes/{process_id}/explore")
    page.wait_for_selector("#explorer[data-drawn='1']", state="attached", timeout=60_000)
    latencies = []
    for index, value in enumerate(sweep_values(values, warmup + changes)):
        outcome = page.evaluate(CHANGE, [path, round(value, 6)])
        if outcome["state"] != "drawn":
            raise SystemExit(f"{process_id}: change to {path} = {value} was {outcome['state']}")
        if index >= warmup:
            latencies.append(float(outcome["ms"]))
    return latencies


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--changes", type=int, default=60)
    parser.add_argument("--warmup", type=int, default=10)
    args = parser.parse_args()
    with (
        tempfile.TemporaryDirectory() as tmp,
        deployment("embedded", Path(tmp) / "bench", workers=1) as server,
        chromium() as browser,
        open_page(browser) as offline,
    ):
        for process_id, (path, _, start) in SWEEPS.items():
            ms = measure(offline.page, server.base_url, process_id, args.changes, args.warmup)
            p50, p95 = percentile(ms, 0.5), percentile(ms, 0.95)
            print(f"{process_id} ({start}; {len(ms)} changes of {path}): "
                  f"p50 {p50:.1f} ms p95 {p95:.1f} ms", flush=True)  # fmt: skip
        if offline.external:
            raise SystemExit(f"the explorers loaded from outside: {offline.external}")


if __name__ == "__main__":
    main()
