"""Render one figure per process, from its first worked example, into docs/figures/, and
write docs/figures.md, the page that shows them.

Run after changing a figure: ``.venv/bin/python scripts/render_figures.py``.  Figures
are rendered as the service renders them (``matplotlib.figure.Figure``, Agg), at a
lower resolution to keep the repository small.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matplotlib.figure import Figure  # noqa: E402

from worker.contract import Artifact  # noqa: E402
from worker.registry import default_registry, family_packages  # noqa: E402

FAMILIES = tuple(package.FAMILY.name for package in family_packages())
DPI = 80
OUT = ROOT / "docs" / "figures"


class _Quiet:
    def report_progress(self, percent: float, message: str = "") -> None:
        pass


def main() -> None:
    captured: list[tuple[str, str, Figure]] = []

    def capture(fig: Figure, stem: str, title: str) -> tuple[Artifact, Artifact]:
        captured.append((stem, title, fig))
        return (
            Artifact(f"{stem}.png", "image/png", b"", title),
            Artifact(f"{stem}.svg", "image/svg+xml", b"", title),
        )

    for family in FAMILIES:
        jobs = importlib.import_module(f"worker.families.{family}.jobs")
        for info in pkgutil.iter_modules(jobs.__path__):
            module = importlib.import_module(f"{jobs.__name__}.{info.name}")
            if hasattr(module, "figure_artifacts"):
                module.figure_artifacts = capture  # type: ignore[attr-defined]
    importlib.import_module("worker.studies.outcome").figure_artifacts = capture  # type: ignore[attr-defined]
    OUT.mkdir(parents=True, exist_ok=True)
    lines = [
        "# Figures",
        "",
        "One figure of each process, from its first worked example, as the service renders",
        "it today (`scripts/render_figures.py` regenerates this page; the service's own",
        f"PNGs are {150} dpi, these {DPI}). Every figure passes the figure check",
        "(`tests/figure_check.py`): no overlapping or clipped text, colour bars beside their",
        "axes, every axis labelled with its unit, mathtext for symbols, contour lines",
        "broken only under their labels.",
        "",
        "Contents:",
        "",
        *[f"- [{d.id}](#{d.id})" for d in default_registry()],
        "",
    ]
    for definition in default_registry():
        captured.clear()
        example = definition.examples[0]
        spec = definition.inputs_model.model_validate(dict(example.inputs))
        definition.run(spec, _Quiet())
        stem, title, fig = captured[0]
        name = f"{definition.id}.png"
        fig.savefig(OUT / name, format="png", dpi=DPI, metadata={"Software": None})
        lines += [
            f"## {definition.id}",
            "",
            f"{definition.title}. Example: {example.title}. File `{stem}.png`: {title}.",
            "",
            f"![{title}](figures/{name})",
            "",
        ]
        print(f"wrote docs/figures/{name}")
    (ROOT / "docs" / "figures.md").write_text("\n".join(lines))
    print("wrote docs/figures.md")


if __name__ == "__main__":
    main()
