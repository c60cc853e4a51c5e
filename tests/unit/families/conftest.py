"""Fakes for job tests: a JobContext that records progress, and figures without rendering."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest
from matplotlib.figure import Figure

from worker.contract import Artifact


@dataclass
class RecordingContext:
    """A :class:`worker.contract.JobContext` that keeps every progress report."""

    reports: list[tuple[float, str]] = field(default_factory=list)

    def report_progress(self, percent: float, message: str = "") -> None:
        self.reports.append((percent, message))

    @property
    def percents(self) -> list[float]:
        return [percent for percent, _ in self.reports]


@pytest.fixture
def ctx() -> RecordingContext:
    return RecordingContext()


def unrendered_artifacts(fig: Figure, stem: str, title: str) -> tuple[Artifact, Artifact]:
    """Stands in for figure_artifacts: the figure is built (so its inputs are checked by
    the plotting code) but not rendered, which is most of a job's run time."""
    assert isinstance(fig, Figure)
    return (
        Artifact(f"{stem}.png", "image/png", b"", title),
        Artifact(f"{stem}.svg", "image/svg+xml", b"", title),
    )


@pytest.fixture
def fast_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    """Skip PNG/SVG rendering in tests that check numbers, not plots."""
    from worker.families.planar_serial.jobs import dexterity_map, optimum_artifacts, synthesis

    monkeypatch.setattr(dexterity_map, "figure_artifacts", unrendered_artifacts)
    monkeypatch.setattr(synthesis, "figure_artifacts", unrendered_artifacts)
    monkeypatch.setattr(optimum_artifacts, "figure_artifacts", unrendered_artifacts)
