"""A design study's page as an explorer: its designs as one flat table (sorted,
filtered and paged by the server: the links work without JavaScript, and
``study-explorer.js`` fetches ``/v1/jobs/{jobID}/designs`` instead of reloading), the
objective-space scatter, the infeasible designs by reason with counts, and the chunk
jobs while it runs.  Each design can be opened as a job of its own, or its inputs edited
in the process form first (:mod:`service.pages.study_actions`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any
from urllib.parse import urlencode

from fastapi import Request

from service.deps import Api
from service.study_labels import column_label
from service.study_tables import STUDY_PROCESS, study_table
from worker.contract import JobRecord, JobStatus
from worker.store.records import JobFilter
from worker.studies.design_table import (
    DesignQuery,
    DesignQueryError,
    DesignTable,
    DesignTables,
    design_page,
)
from worker.studies.reason_groups import reason_groups

__all__ = ["PAGE_ROWS", "study_context"]

#: Designs per page of the table.
PAGE_ROWS = 25
#: Chunk jobs listed while a study runs (the first ones).
LISTED_CHUNKS = 200
_FILTERS = ("sort", "feasible", "pareto", "reason", "cursor")


def _flag(value: str | None) -> bool | None:
    return {"true": True, "false": False}.get(value or "")


def _number(value: float | None) -> str:
    return "–" if value is None else f"{value:.6g}"


def _chunks(api: Api, job: JobRecord) -> list[dict[str, str]]:
    page = api.store.list_jobs(limit=LISTED_CHUNKS, where=JobFilter(parent_id=job.job_id),
                               owner=api.identity.owner_scope)  # fmt: skip
    return [{"id": c.job_id, "status": c.status.value, "message": c.message}
            for c in reversed(page.jobs)]  # fmt: skip


def _table_context(job: JobRecord, table: DesignTable, params: Mapping[str, str]) -> dict[str, Any]:
    query = DesignQuery(sort=params.get("sort") or None, feasible=_flag(params.get("feasible")),
                        pareto=_flag(params.get("pareto")),
                        reason=params.get("reason") or None)  # fmt: skip
    notice = ""
    try:
        page = design_page(table, query, PAGE_ROWS, params.get("cursor") or None)
    except DesignQueryError as exc:  # a hand-edited address: the first page, and why
        notice = f"{exc} (showing the first page, unsorted)."
        query = DesignQuery()
        page = design_page(table, query, PAGE_ROWS, None)
    base = f"/v1/jobs/{job.job_id}"
    kept = {k: v for k, v in params.items() if k in ("feasible", "pareto", "reason") and v}

    def href(**change: str) -> str:
        merged = {**kept, **({"sort": query.sort} if query.sort else {}), **change}
        return f"{base}?{urlencode({k: v for k, v in merged.items() if v})}#designs"

    columns = [
        {"key": c.key, "label": column_label(c), "kind": c.kind, "goal": c.goal,
         "sort_href": href(sort=("-" if query.sort == c.key else "") + c.key),
         "sorted": "ascending" if query.sort == c.key else
                   "descending" if query.sort == f"-{c.key}" else ""}
        for c in table.columns
    ]  # fmt: skip
    rows = [
        {**row, "cells": [_number(row["values"][c.key]) for c in table.columns]}
        for row in page["designs"]
    ]
    objectives = [c.key for c in table.columns if c.kind == "objective"]
    parameters = [c.key for c in table.columns if c.kind == "parameter"]
    axes = (objectives + parameters)[:2] if len(objectives) < 2 else objectives[:2]
    return {
        "columns": columns,
        "index_href": href(sort="-index" if query.sort == "index" else "index"),
        "rows": rows,
        "matched": page["matched"],
        "total": page["total"],
        "next_href": href(cursor=page["next_cursor"]) if page["next_cursor"] else "",
        "first_href": href() if params.get("cursor") else "",
        "filters": {
            "feasible": params.get("feasible", ""),
            "pareto": params.get("pareto", ""),
            "reason": query.reason or "",
            "sort": query.sort or "",
        },
        "notice": notice,
        "data_href": f"{base}/designs",
        "scatter_href": (
            f"{base}/designs/scatter?{urlencode({'x': axes[0], 'y': axes[1]})}"
            if len(axes) == 2
            else ""
        ),
    }


def study_context(
    request: Request, api: Api, job: JobRecord, result: Mapping[str, Any] | None
) -> dict[str, Any]:
    """The ``study`` part of a design study's job page ({} for any other job)."""
    if job.process_id != STUDY_PROCESS:
        return {}
    study: dict[str, Any] = {"chunks": [], "reasons": [], "table": None}
    if job.status in (JobStatus.ACCEPTED, JobStatus.RUNNING):
        study["chunks"] = _chunks(api, job)
    if result is not None and job.status is JobStatus.SUCCESSFUL:
        study["reasons"] = reason_groups(result.get("infeasible_reasons") or [])
        tables: DesignTables = request.app.state.design_tables
        params = {k: v for k, v in request.query_params.items() if k in _FILTERS}
        _, table = study_table(tables, api, job.job_id)
        study["table"] = _table_context(job, table, params)
    return {"study": study}
