"""What each page shows: the context of every template, from the stored records.

Route handlers fetch (store, registry) and call one of these; nothing here touches the
store or does blocking work beyond reading a method page from disk.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from typing import Any
from urllib.parse import urlencode

from fastapi import Request
from fastapi.responses import HTMLResponse

from service.documents import artifact_link, as_json, job_href, status_document
from service.pages.data_charts import data_chart_context
from service.pages.input_table import input_rows
from service.pages.job_timing import duration_s, duration_text, job_timing
from service.pages.json_text import compact_json
from service.pages.own_arm import own_arm_form
from service.pages.quantities import job_quantities
from service.pages.renderer import Pages
from service.pages.result_view import result_view
from service.problems import PROBLEM_TYPES, problem_document
from worker.contract import ArtifactInfo, JobRecord, JobStatus
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.result_paths import plain_symbol
from worker.store.base import JobPage

__all__ = [
    "ExampleForm",
    "compact_json",
    "example_forms",
    "job_list_page",
    "job_page",
    "landing_page",
    "method_list_page",
    "method_page",
    "process_list_page",
    "process_page",
]

ExampleForm = dict[str, Any]

_PLOTS = ("image/png", "image/svg+xml")
_DOWNLOADS = frozenset({"text/csv", "application/x-npz"})
#: The result members the job page shows under "Provenance", not among the results.
PROVENANCE_KEYS = ("provenance", "result_hash", "reused_from")


def landing_page(request: Request, pages: Pages, registry: ProcessRegistry) -> HTMLResponse:
    return pages.render(request, "landing.html", {"families": pages.families(registry)})


def process_list_page(request: Request, pages: Pages, registry: ProcessRegistry) -> HTMLResponse:
    return pages.render(request, "processes.html", {"families": pages.families(registry)})


def _rows(text: str) -> int:
    return min(max(text.count("\n") + 2, 4), 24)


def example_forms(definition: ProcessDefinition) -> list[ExampleForm]:
    """One form per worked example, pre-filled with its inputs (one empty form for a
    process without examples)."""
    forms: list[ExampleForm] = [
        {
            "title": ex.title,
            "description": ex.description,
            "text": compact_json(dict(ex.inputs)),
            "problem": None,
        }
        for ex in definition.examples
    ]
    if not forms:
        forms = [
            {
                "title": "Your inputs",
                "description": "Write the inputs as JSON.",
                "text": "{}",
                "problem": None,
            }
        ]
    for form in forms:
        form["rows"] = _rows(form["text"])
    return forms


def process_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    definition: ProcessDefinition,
    *,
    examples: Sequence[ExampleForm] | None = None,
    status_code: int = 200,
    template: str = "process.html",
    extra: Mapping[str, Any] | None = None,
) -> HTMLResponse:
    """A process's page; ``examples`` replaces the worked-example forms (a re-rendered
    form keeps the user's text and shows its problem); ``template`` (one extending
    process.html) draws it with ``extra`` added to its context."""
    family = next(
        (f.title for f in pages.families(registry) if definition in f.processes), "Processes"
    )
    method = pages.methods.page(definition.method_doc) if definition.method_doc else None
    context = {
        "process": definition,
        "family_title": family,
        "method": method,
        "examples": examples if examples is not None else example_forms(definition),
        "inputs": input_rows(definition.inputs_schema),
        "result_paths": [
            {**entry.describe(), "symbol": plain_symbol(entry.symbol) if entry.symbol else ""}
            for entry in definition.result_paths
        ],
        "own_arm": own_arm_form(definition),
        **(extra or {}),
    }
    return pages.render(request, template, context, status_code=status_code)


def job_list_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    page: JobPage,
    *,
    limit: int,
    status: JobStatus | None,
    process_id: str | None,
    owner: str | None = None,
) -> HTMLResponse:
    filters: dict[str, str] = {"limit": str(limit)}
    if status is not None:
        filters["status"] = status.value
    if process_id:
        filters["processID"] = process_id
    if owner is not None:  # an admin's listing of one key's jobs
        filters["owner"] = owner
    next_href = (
        f"/v1/jobs?{urlencode({**filters, 'cursor': page.next_cursor})}" if page.next_cursor else ""
    )
    first_href = f"/v1/jobs?{urlencode(filters)}" if "cursor" in request.query_params else ""
    query = dict(request.query_params)
    query["f"] = "json"
    now = datetime.now(UTC)
    context = {
        "jobs": [
            {**as_json(status_document(j)), "duration": duration_text(duration_s(j, now))}
            for j in page.jobs
        ],
        "live": any(j.status in (JobStatus.ACCEPTED, JobStatus.RUNNING) for j in page.jobs),
        "statuses": [s.value for s in JobStatus],
        "process_ids": registry.ids(),
        "status": status.value if status is not None else "",
        "process_id": process_id or "",
        "limit": limit,
        "next_href": next_href,
        "first_href": first_href,
        "json_href": f"/v1/jobs?{urlencode(query)}",
        "compare": True,
    }
    return pages.render(request, "jobs.html", context)


def _failure(job: JobRecord) -> dict[str, Any] | None:
    if job.status is JobStatus.DISMISSED:
        return problem_document(
            "job-dismissed", detail="This job was dismissed; it has no results."
        )
    if job.status is not JobStatus.FAILED:
        return None
    error = dict(job.error or {})
    slug = str(error.get("type") or "job-failed")
    status, title, _ = PROBLEM_TYPES.get(slug, PROBLEM_TYPES["job-failed"])
    return problem_document(
        slug,
        detail=str(error.get("detail") or "The job failed."),
        status=status,
        title=str(error.get("title") or title),
    )


def _plots(artifacts: Sequence[ArtifactInfo], base: str) -> list[dict[str, str]]:
    """One image per plot: its PNG, else its SVG."""
    by_stem: dict[str, ArtifactInfo] = {}
    for artifact in artifacts:
        if artifact.media_type not in _PLOTS:
            continue
        stem = artifact.name.rsplit(".", 1)[0]
        known = by_stem.get(stem)
        if known is None or artifact.media_type == "image/png":
            by_stem[stem] = artifact
    return [
        {"name": a.name, "title": a.title, "href": f"{base}/results/{a.name}"}
        for a in by_stem.values()
    ]


def _warnings(result: Mapping[str, Any]) -> list[str]:
    """``summary.warnings`` of a result: what makes it hold less than it seems to (an
    empty map, a task point out of reach), shown apart on the page."""
    summary = result.get("summary")
    warnings = summary.get("warnings") if isinstance(summary, Mapping) else None
    return [str(w) for w in warnings] if isinstance(warnings, list) else []


def _notes(result: Mapping[str, Any], warnings: Sequence[str]) -> list[dict[str, Any]]:
    notes = result.get("notes")
    errata = result.get("paper_errata")
    marked = {str(e) for e in errata} if isinstance(errata, list) else set()
    if not isinstance(notes, list):
        return []
    return [
        {"text": str(n), "erratum": str(n) in marked, "warning": str(n) in warnings} for n in notes
    ]


def job_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    job: JobRecord,
    result: Mapping[str, Any] | None,
    *,
    template: str = "job.html",
    extra: Mapping[str, Any] | None = None,
) -> HTMLResponse:
    """A job's page: status (live while it runs), the failure, the plots, the notes,
    the result as tables, the downloads and the inputs; ``template`` (one extending
    job.html) draws it with ``extra`` added to its context."""
    document = as_json(status_document(job))
    definition = registry.get(job.process_id)
    finished = job.status in (JobStatus.SUCCESSFUL, JobStatus.FAILED)
    live = job.status in (JobStatus.ACCEPTED, JobStatus.RUNNING)
    context: dict[str, Any] = {
        "job": document,
        "job_inputs": dict(job.inputs),
        "process_title": definition.title if definition is not None else job.process_id,
        # a study's chunk has no process page of its own: its title leads to the study
        "process_href": f"/v1/processes/{job.process_id}"
        if definition is not None
        else job_href(job.parent_id)
        if job.parent_id
        else "",
        "live": live,
        "finished": finished,
        "dismiss_label": ("Cancel this job" if live else "Delete the results" if finished else ""),
        "timing": job_timing(job, datetime.now(UTC)),
        "rerun_href": f"/pages/jobs/{job.job_id}/edit" if definition is not None else "",
        "problem": _failure(job),
        "plots": [],
        "data_chart": {},
        "notes": [],
        "warnings": [],
        "errata_count": 0,
        "result": None,
        "downloads": [],
        "provenance": None,
    }
    if result is not None and job.status is JobStatus.SUCCESSFUL:
        warnings = _warnings(result)
        notes = _notes(result, warnings)
        context.update(
            plots=_plots(job.artifacts, f"/v1/jobs/{job.job_id}"),
            data_chart=data_chart_context(definition, job),
            notes=notes,
            warnings=warnings,
            errata_count=sum(1 for n in notes if n["erratum"]),
            result=result_view(
                result,
                leave_out=("notes", "paper_errata", *PROVENANCE_KEYS),
                quantities=job_quantities(definition, result, job.inputs),
            ),
            downloads=[
                {
                    **as_json(artifact_link(job_href(job.job_id), a)),
                    "download": a.media_type in _DOWNLOADS,
                }
                for a in job.artifacts
            ],
            provenance={
                **({"reused_from": document["reused_from"]} if "reused_from" in document else {}),
                **{k: result[k] for k in PROVENANCE_KEYS if k in result},
            }
            or None,
        )
    context.update(extra or {})
    return pages.render(request, template, context)


def method_list_page(request: Request, pages: Pages, registry: ProcessRegistry) -> HTMLResponse:
    methods = []
    for slug in pages.methods.slugs():
        page = pages.methods.page(slug)
        if page is None:  # pragma: no cover - removed between listing and reading
            continue
        processes = [d for d in registry if d.method_doc == slug]
        methods.append({"slug": slug, "title": page.title, "processes": processes})
    context = {"methods": methods, "docs_dir": str(pages.settings.docs_dir)}
    return pages.render(request, "methods.html", context)


def method_page(
    request: Request, pages: Pages, registry: ProcessRegistry, slug: str
) -> HTMLResponse | None:
    """The method page ``slug``, or None if there is none."""
    page = pages.methods.page(slug)
    if page is None:
        return None
    processes = [d for d in registry if d.method_doc == slug]
    return pages.render(request, "method.html", {"method": page, "processes": processes})
