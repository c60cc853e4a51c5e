"""The pages that act on one job: its inputs back in the process form ("Edit and run
again"), and the question before it is dismissed (the step that works without
JavaScript; with it, the job page asks in a dialog and posts directly)."""

from __future__ import annotations

from typing import Any

from fastapi import Request
from fastapi.responses import HTMLResponse

from service.documents import as_json, status_document
from service.pages.renderer import Pages
from service.pages.views import ExampleForm, compact_json, example_forms, process_page
from worker.contract import JobRecord, JobStatus
from worker.processes import ProcessDefinition, ProcessRegistry

__all__ = ["dismiss_question_page", "rerun_form", "rerun_page"]

#: Rows of the inputs box at most (it scrolls beyond).
_MAX_ROWS = 24


def _tidy(value: Any) -> Any:
    """Whole numbers stored as floats (``30.0``) written as people type them (``30``):
    the same JSON number to the service."""
    if isinstance(value, float) and value.is_integer() and abs(value) < 2**53:
        return int(value)
    if isinstance(value, list):
        return [_tidy(v) for v in value]
    if isinstance(value, dict):
        return {k: _tidy(v) for k, v in value.items()}
    return value


def rerun_form(job_id: str, text: str) -> ExampleForm:
    """The form holding job ``job_id``'s inputs as ``text`` (JSON), first on the page;
    it posts ``from`` so that a refused run comes back in this form."""
    return {
        "title": f"Edit and run again: the inputs of job {job_id[:8]}",
        "description": "These are the inputs that job ran with; change what you like "
        "and run them as a new job.",
        "text": text,
        "problem": None,
        "rows": min(max(text.count("\n") + 2, 4), _MAX_ROWS),
        "button": "Run as a new job",
        "source_job": job_id,
    }


def rerun_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    definition: ProcessDefinition,
    job: JobRecord,
) -> HTMLResponse:
    """The process page with a first form holding ``job``'s inputs, ready to edit and
    run; the worked examples follow."""
    rerun = rerun_form(job.job_id, compact_json(_tidy(dict(job.inputs))))
    return process_page(request, pages, registry, definition,
                        examples=[rerun, *example_forms(definition)])  # fmt: skip


def dismiss_question_page(
    request: Request, pages: Pages, registry: ProcessRegistry, job: JobRecord
) -> HTMLResponse:
    """The confirmation step before ``job`` is dismissed: the question (the
    ``dismiss_question`` macro, which the job page's dialog asks too), a button that
    posts the dismissal, and a way back."""
    live = job.status in (JobStatus.ACCEPTED, JobStatus.RUNNING)
    definition = registry.get(job.process_id)
    context = {
        "job": as_json(status_document(job)),
        "process_title": definition.title if definition is not None else job.process_id,
        "action": "Cancel this job" if live else "Delete the results",
        "danger": not live,
    }
    return pages.render(request, "dismiss.html", context)
