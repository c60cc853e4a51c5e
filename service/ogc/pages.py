"""The façade's pages: every ``/ogc`` GET resource as HTML (conformance class ``html``).

A page is an HTML 5 document holding what its JSON document holds and every link of
it as an ``<a>`` (18-062r2, /req/html/content).  Where the native pages show the same
thing (a process, the processes, a job, the jobs) their templates are reused, with the
OGC document's own members and links added (``templates/ogc/``, each extending the
native one); the landing page and the conformance declaration have pages of their own.

The links of a page are those of the JSON document as the HTML representation has
them (:func:`page_links`): ``self`` is the page and ``alternate`` the JSON (``f=json``);
every other link is kept as it is.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any
from urllib.parse import urlencode

from fastapi import Request
from fastapi.responses import HTMLResponse

from service.ogc.outputs import OutputSpec
from service.ogc.results import SelectedOutput
from service.ogc.urls import PublicUrls, self_and_alternate, with_format
from service.ogc.vocabulary import HTML, JSON
from service.pages import Pages, views
from service.pages.result_view import result_view
from worker.contract import JobRecord, JobStatus
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.store.base import StoredArtifact

__all__ = [
    "NEGOTIATED",
    "conformance_page",
    "job_list_page",
    "job_page",
    "landing_page",
    "output_page",
    "page_links",
    "process_list_page",
    "process_page",
    "results_page",
]

#: The headers of a JSON answer of a resource that also answers pages.
NEGOTIATED: Mapping[str, str] = MappingProxyType({"Vary": "Accept"})

#: The job-list filters the page's form does not have a field for (kept as they are).
_KEPT_FILTERS = ("type", "datetime", "minDuration", "maxDuration")

#: Files an output page shows inline.
_PLOTS = frozenset({"image/png", "image/svg+xml"})


def page_links(links: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The links of the page for a JSON document with ``links``: ``self`` becomes the
    ``alternate`` JSON (``f=json``), the ``alternate`` page becomes ``self``; the rest
    stay as they are."""
    own: list[dict[str, Any]] = []
    rest: list[dict[str, Any]] = []
    for link in links:
        if link.get("rel") == "self":
            title = f"{link.get('title') or 'this document'} as JSON"
            href = with_format(link["href"], "json")
            own.append({**link, "rel": "alternate", "href": href, "title": title})
        elif link.get("rel") == "alternate" and link.get("type") == HTML:
            own.insert(0, {**link, "rel": "self"})
        else:
            rest.append(dict(link))
    return [*own, *rest]


def _alternate(links: Sequence[Mapping[str, Any]]) -> str:
    """The other representation: the page of a JSON document, the JSON of a page."""
    return str(next(link["href"] for link in links if link.get("rel") == "alternate"))


def _plain(value: Any) -> str:
    if isinstance(value, list):
        return ", ".join(str(item) for item in value)
    return str(value)


def _facts(document: Mapping[str, Any], leave_out: Sequence[str] = ()) -> list[tuple[str, str]]:
    """The document's members that are values or lists of values, as text."""
    return [
        (name, _plain(value))
        for name, value in document.items()
        if name not in leave_out
        and not isinstance(value, dict)
        and not (isinstance(value, list) and any(isinstance(v, dict | list) for v in value))
    ]


def _common(urls: PublicUrls, document: Mapping[str, Any]) -> dict[str, Any]:
    links = page_links(document.get("links", ()))
    return {
        "document": document,
        "links": links,
        "json_href": _alternate(links),
        "landing_href": with_format(f"{urls.ogc}/", "html"),
    }


def landing_page(
    request: Request, pages: Pages, urls: PublicUrls, document: dict[str, Any]
) -> HTMLResponse:
    return pages.render(request, "ogc/landing.html", _common(urls, document))


def conformance_page(
    request: Request, pages: Pages, urls: PublicUrls, document: dict[str, Any]
) -> HTMLResponse:
    """The declaration has no links of its own: the page links to itself and its JSON."""
    own = self_and_alternate(f"{urls.ogc}/conformance", "the conformance declaration")
    return pages.render(request, "ogc/conformance.html", _common(urls, {**document, "links": own}))


def process_list_page(
    request: Request,
    pages: Pages,
    urls: PublicUrls,
    definitions: Sequence[ProcessDefinition],
    document: dict[str, Any],
) -> HTMLResponse:
    """A page of process summaries (``definitions``, by family), with the next page."""
    next_href = next((x["href"] for x in document["links"] if x["rel"] == "next"), None)
    context = {
        **_common(urls, document),
        "families": pages.families(definitions),
        "summaries": {
            s["id"]: {"doc": s, "page": _alternate(s["links"])} for s in document["processes"]
        },
        "next_href": with_format(next_href, "html") if next_href else "",
    }
    return pages.render(request, "ogc/processes.html", context)


def process_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    urls: PublicUrls,
    definition: ProcessDefinition,
    document: dict[str, Any],
) -> HTMLResponse:
    """The process page with the OGC description's members, inputs, outputs and links."""
    extra = {
        **_common(urls, document),
        "facts": _facts(document, leave_out=("title", "description")),
        "list_href": with_format(f"{urls.ogc}/processes", "html"),
    }
    return views.process_page(
        request, pages, registry, definition, template="ogc/process.html", extra=extra
    )


def job_list_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    urls: PublicUrls,
    document: dict[str, Any],
    limit: int,
) -> HTMLResponse:
    """A page of status information with the OGC filters of the request (``status``
    and ``processID`` chosen in the form, the others kept as they are)."""
    params = [(k, v) for k, v in request.query_params.multi_items() if k != "f"]
    next_href = next((x["href"] for x in document["links"] if x["rel"] == "next"), None)
    unfiltered = f"{urls.ogc}/jobs"
    first = [(k, v) for k, v in params if k != "cursor"]
    first_href = with_format(f"{unfiltered}?{urlencode(first)}", "html")
    context = {
        **_common(urls, document),
        "jobs": document["jobs"],
        "job_pages": {info["jobID"]: _alternate(info["links"]) for info in document["jobs"]},
        "statuses": [s.value for s in JobStatus],
        "process_ids": registry.ids(),
        "chosen_statuses": {v for k, v in params if k == "status"},
        "chosen_processes": {v for k, v in params if k == "processID"},
        "kept_filters": [(k, v) for k, v in params if k in _KEPT_FILTERS],
        "limit": limit,
        "filtered": any(k not in ("limit", "cursor") for k, _ in params),
        "form_action": unfiltered,
        "unfiltered_href": with_format(unfiltered, "html"),
        "processes_href": with_format(f"{urls.ogc}/processes", "html"),
        "next_href": with_format(next_href, "html") if next_href else "",
        "first_href": first_href if any(k == "cursor" for k, _ in params) else "",
    }
    return pages.render(request, "ogc/jobs.html", context)


def _job_context(urls: PublicUrls, document: dict[str, Any]) -> dict[str, Any]:
    return {
        **_common(urls, document),
        "facts": _facts(document),
        "list_href": with_format(f"{urls.ogc}/jobs", "html"),
        "outputs": None,
        "response": "",
    }


def job_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    urls: PublicUrls,
    job: JobRecord,
    result: Mapping[str, Any] | None,
    document: dict[str, Any],
) -> HTMLResponse:
    """The job page with the status information's members and links."""
    extra = _job_context(urls, document)
    return views.job_page(
        request, pages, registry, job, result, template="ogc/job.html", extra=extra
    )


def results_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    urls: PublicUrls,
    job: JobRecord,
    result: Mapping[str, Any],
    document: dict[str, Any],
    selected: Sequence[SelectedOutput],
    response: str,
) -> HTMLResponse:
    """A finished job's results: the job page with the outputs the execute request
    selected, each linked where a client fetches it (by value or by reference)."""
    href = urls.results(job.job_id)
    extra = _job_context(urls, document)
    extra["links"] = [
        {"href": with_format(href, "html"), "rel": "self", "type": HTML, "title": "these results"},
        {
            "href": with_format(href, "json"),
            "rel": "alternate",
            "title": "the results as the execute request asked",
        },
        {"href": urls.job(job.job_id), "rel": "up", "type": JSON, "title": "the job's status"},
    ]
    extra["json_href"] = with_format(href, "json")
    extra["outputs"] = [
        {
            "id": output.spec.id,
            "title": output.spec.title,
            "media_type": output.spec.media_type,
            "mode": output.mode,
            "href": output.href(urls, job.job_id),
        }
        for output in selected
    ]
    extra["response"] = response
    return views.job_page(
        request, pages, registry, job, result, template="ogc/job.html", extra=extra
    )


def output_page(
    request: Request,
    pages: Pages,
    urls: PublicUrls,
    job: JobRecord,
    spec: OutputSpec,
    value: Any = None,
    stored: StoredArtifact | None = None,
) -> HTMLResponse:
    """One output of a finished job: a result member's ``value`` as tables, or a file
    (``stored``): a plot inline, any file as a link to its bytes."""
    href = urls.output(job.job_id, spec.id)
    links = [
        {"href": with_format(href, "html"), "rel": "self", "type": HTML, "title": "this output"},
        {
            "href": with_format(href, "json"),
            "rel": "alternate",
            "type": spec.media_type,
            "title": "the output itself",
        },
        {"href": urls.results(job.job_id), "rel": "up", "title": "the job's results"},
    ]
    if stored is not None:
        links.append(
            {
                "href": urls.artifact(job.job_id, spec.id),
                "rel": "enclosure",
                "type": spec.media_type,
                "title": f"download {spec.id}",
            }
        )
    context = {
        "job_id": job.job_id,
        "process_id": job.process_id,
        "output": spec,
        "view": result_view({spec.id: value}) if stored is None else None,
        "image": urls.artifact(job.job_id, spec.id) if spec.media_type in _PLOTS else "",
        "size": stored.info.size if stored is not None else None,
        "links": links,
        "json_href": with_format(href, "json"),
        "landing_href": with_format(f"{urls.ogc}/", "html"),
        "job_href": with_format(urls.job(job.job_id), "html"),
        "results_href": with_format(urls.results(job.job_id), "html"),
    }
    return pages.render(request, "ogc/output.html", context)
