"""Showing a job's progress while the client waits: a Rich bar in a terminal, an updating
line in Jupyter, nothing elsewhere (a pipe, a log file, a CI job)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

from dexlab.documents import JobStatus
from dexlab.notebook import NotebookProgress, notebook_shell

if TYPE_CHECKING:
    from rich.console import Console

__all__ = ["ProgressDisplay", "SilentProgress", "TerminalProgress", "progress_display"]


@runtime_checkable
class ProgressDisplay(Protocol):
    """Something that shows a job's status as it changes."""

    def update(self, status: JobStatus) -> None: ...

    def close(self) -> None: ...


class SilentProgress:
    """Shows nothing."""

    def update(self, status: JobStatus) -> None:
        """Nothing to show."""

    def close(self) -> None:
        """Nothing to close."""


class TerminalProgress:
    """A Rich progress bar on stderr: the job, the bar, the percentage, the time
    elapsed and left (estimated from the progress so far), and the job's message."""

    def __init__(self, label: str, console: Console | None = None) -> None:
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            Progress,
            TaskProgressColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self._progress = Progress(
            TextColumn("[bold]{task.fields[label]}"),
            BarColumn(),
            TaskProgressColumn(),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            TextColumn("{task.description}"),
            console=console or Console(stderr=True),
        )
        self._task = self._progress.add_task("submitted", total=100, label=label)
        self._progress.start()

    def update(self, status: JobStatus) -> None:
        text = f"{status.status}: {status.message}" if status.message else status.status
        self._progress.update(self._task, completed=status.progress, description=text)

    def close(self) -> None:
        self._progress.stop()


def progress_display(show: bool | ProgressDisplay, label: str) -> ProgressDisplay:
    """The display for ``show``: a given display as is; for True, a notebook display
    inside a Jupyter kernel, a Rich bar when stderr is a terminal, else nothing."""
    if isinstance(show, ProgressDisplay):
        return show
    if not show:
        return SilentProgress()
    if notebook_shell() is not None:
        return NotebookProgress(label)
    from rich.console import Console

    console = Console(stderr=True)
    return TerminalProgress(label, console) if console.is_terminal else SilentProgress()
