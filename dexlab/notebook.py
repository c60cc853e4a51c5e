"""Jobs in Jupyter: the HTML a job shows itself as, and a progress display that updates.

Every piece of text from the service (messages, notes, titles, errors) is escaped; plots
are inlined as ``<img>`` with the PNG's bytes in base64.  Nothing here needs ipywidgets:
the progress display is one HTML output (an HTML ``<progress>`` element) replaced in
place through IPython's display handles, and everything degrades to nothing where
IPython is absent.
"""

from __future__ import annotations

import base64
import importlib
import sys
from collections.abc import Iterable, Mapping, Sequence
from html import escape
from typing import Any

from dexlab.documents import Artifact, JobStatus

__all__ = ["NotebookProgress", "job_html", "notebook_shell", "progress_html"]

#: A plot shown inline: its artifact and its PNG bytes, or why it could not be fetched.
Plot = tuple[Artifact, bytes | str]


def notebook_shell() -> Any | None:
    """The running IPython kernel's shell, or None outside a notebook (IPython is only
    looked up if something already imported it)."""
    ipython = sys.modules.get("IPython")
    if ipython is None:
        return None
    try:
        shell = ipython.get_ipython()
    except AttributeError:  # pragma: no cover - a partial IPython
        return None
    return shell if shell is not None and getattr(shell, "kernel", None) is not None else None


def _bar(status: JobStatus) -> str:
    return (
        f'<progress max="100" value="{int(status.progress)}" style="width: 20em">'
        f"{int(status.progress)}%</progress>"
    )


def progress_html(label: str, status: JobStatus) -> str:
    """One line: the job's label, a progress bar, the percentage, status and message."""
    message = f": {escape(status.message)}" if status.message else ""
    return (
        f'<div class="dexlab-progress"><strong>{escape(label)}</strong> {_bar(status)} '
        f"{int(status.progress)}% <em>{escape(status.status)}</em>{message}</div>"
    )


def _notes_html(notes: Iterable[Any]) -> str:
    items = "".join(f"<li>{escape(str(note))}</li>" for note in notes)
    return f'<ul class="dexlab-notes">{items}</ul>' if items else ""


def _plot_html(artifact: Artifact, png: bytes | str) -> str:
    caption = escape(f"{artifact.title} ({artifact.name})" if artifact.title else artifact.name)
    if isinstance(png, str):  # the plot could not be fetched: say why
        return f'<p class="dexlab-plot-error">{caption}: {escape(png)}</p>'
    data = base64.b64encode(png).decode("ascii")
    return (
        f'<figure style="margin: 0.5em 0"><img alt="{escape(artifact.title or artifact.name)}" '
        f'src="data:image/png;base64,{data}" style="max-width: 100%"/>'
        f"<figcaption>{caption}</figcaption></figure>"
    )


def job_html(
    status: JobStatus,
    *,
    notes: Sequence[Any] = (),
    plots: Sequence[Plot] = (),
    files: Sequence[Artifact] = (),
) -> str:
    """A job as HTML: process, ID, status and progress; the failure if it failed; its
    notes, its plots inline and the list of its files."""
    head = (
        f"<p><strong>{escape(status.process_id)}</strong> job "
        f"<code>{escape(status.job_id)}</code>: <strong>{escape(status.status)}</strong>"
    )
    head += f" &mdash; {escape(status.message)}</p>" if status.message else "</p>"
    parts = [head]
    if not status.done:
        parts.append(f"<p>{_bar(status)} {int(status.progress)}%</p>")
    if status.error:
        error: Mapping[str, Any] = status.error
        title = escape(str(error.get("title") or error.get("type") or "failed"))
        parts.append(f'<p class="dexlab-error"><strong>{title}</strong>: '
                     f'{escape(str(error.get("detail") or ""))}</p>')  # fmt: skip
    parts.append(_notes_html(notes))
    parts.extend(_plot_html(artifact, png) for artifact, png in plots)
    if files:
        listed = ", ".join(f"<code>{escape(a.name)}</code>" for a in files)
        parts.append(f"<p>Files: {listed}</p>")
    return '<div class="dexlab-job">' + "".join(parts) + "</div>"


class NotebookProgress:
    """A progress line in a notebook's output, updated in place."""

    def __init__(self, label: str) -> None:
        shown: Any = importlib.import_module("IPython.display")  # present: a kernel runs

        self._label = label
        self._html = shown.HTML
        self._handle = shown.display(
            shown.HTML(f"<div>{escape(label)}: submitted</div>"), display_id=True
        )

    def update(self, status: JobStatus) -> None:
        if self._handle is not None:
            self._handle.update(self._html(progress_html(self._label, status)))

    def close(self) -> None:
        """Nothing to release: the last state stays in the output."""
