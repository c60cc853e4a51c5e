"""``/v1/jobs/{jobID}/designs``: a finished design study's designs, paged, sorted and
filtered, and two of their columns as a scatter (the study page's explorer draws both).

The table is the study's ``designs.npz``, read once per stored file
(:mod:`worker.studies.design_table`); the caller must see the study as for its results
(another owner's is 404).  A job that is not a design study, or has no designs file,
is ``404 no-such-artifact``; one not finished, ``result-not-ready`` as for its results.
"""

from __future__ import annotations

from typing import Annotated, Any
from urllib.parse import urlencode

from fastapi import APIRouter, Query, Request
from pydantic import AfterValidator, BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from service.deps import ApiDep
from service.problems import parameter_error
from service.schemas import Link
from service.study_labels import column_label
from service.study_tables import study_table
from worker.studies.design_table import (
    DesignQuery,
    DesignQueryError,
    DesignTable,
    design_page,
    design_scatter,
    read_cursor,
)
from worker.studies.reason_groups import reason_groups

__all__ = ["DesignPage", "DesignScatter", "ReasonGroups", "router"]

router = APIRouter(prefix="/v1/jobs", tags=["jobs"])

_KEY = r"^-?[A-Za-z0-9_]{1,200}$"


class _Document(BaseModel):
    model_config = ConfigDict(extra="forbid")


class DesignColumnDocument(_Document):
    key: str = Field(description="The column's name in `sort`, `range`, `x` and `y`.")
    path: str = Field(description="The study's varied input or objective (result path).")
    kind: str = Field(description="parameter (a varied input) or objective.")
    unit: str
    symbol: str = Field(description="The declared symbol (mathtext, e.g. `$d_z$`).")
    label: str = Field(description="For axes and headers: the symbol as plain text (or the "
                       "path) with the unit, e.g. `d_z` or `l_i [cm]`.")  # fmt: skip
    goal: str = Field(description="max or min for an objective; '' for a parameter.")
    description: str = Field(description="What the number is (the process's result path).")


class DesignRow(_Document):
    index: int = Field(description="The design's index in the study.")
    feasible: bool
    pareto: bool = Field(description="Non-dominated among the feasible designs.")
    reason_code: str | None = Field(description="refused, no-value or failed; null if feasible.")
    reason_field: str | None = Field(description="The input a refusal names, if any.")
    values: dict[str, float | None] = Field(description="Column key -> value (null: none).")


class DesignPage(_Document):
    """``GET /v1/jobs/{jobID}/designs``."""

    jobID: str
    process: str = Field(description="The process the study ran.")
    total: int = Field(description="Designs in the study.")
    matched: int = Field(description="Designs the filters keep.")
    columns: list[DesignColumnDocument]
    designs: list[DesignRow]
    links: list[Link]


class ScatterPoints(_Document):
    index: list[int]
    x: list[float]
    y: list[float]
    pareto: list[bool]


class ScatterBins(_Document):
    x_edges: list[float]
    y_edges: list[float]
    counts: list[list[int]] = Field(description="Designs per bin, indexed [x][y].")


class DesignScatter(_Document):
    """``GET /v1/jobs/{jobID}/designs/scatter``."""

    jobID: str
    x: str
    y: str
    matched: int = Field(description="Designs with both values that the filters keep.")
    points: ScatterPoints = Field(description="Every design; when binned, the Pareto ones.")
    bins: ScatterBins | None = Field(description="Beyond 10,000 designs: 100 x 100 bins.")


def _cursor(value: str | None) -> str | None:
    if value is not None:
        try:
            read_cursor(value)
        except DesignQueryError as exc:
            raise ValueError(str(exc)) from None
    return value


Cursor = Annotated[
    str | None,
    Query(max_length=500, description="Where a `next` link continues."),
    AfterValidator(_cursor),
]


class ReasonGroup(_Document):
    reason_code: str = Field(description="refused, no-value or failed.")
    reason_field: str = Field(description="The input a refusal names; '' if none.")
    reason: str = Field(description="The message with the numbers it quotes as '…'.")
    example: str = Field(description="The group's most frequent message, numbers and all.")
    messages: int = Field(description="Distinct messages in the group.")
    designs: int = Field(description="Infeasible designs in the group.")


class ReasonGroups(_Document):
    """``GET /v1/jobs/{jobID}/designs/reasons``."""

    jobID: str
    groups: list[ReasonGroup] = Field(description="Most designs first.")


Sort = Annotated[
    str | None,
    Query(pattern=_KEY, description="A column key (`-` first: descending); designs without "
          "a value last. Default: feasible designs first, then by index."),
]  # fmt: skip
Feasible = Annotated[bool | None, Query(description="Only the feasible (or infeasible) ones.")]
Pareto = Annotated[bool | None, Query(description="Only the non-dominated (or dominated) ones.")]
Range = Annotated[
    list[str] | None,
    Query(alias="range", max_length=20, description="`key:low:high` (either end may be "
          "empty): designs whose column lies within; repeat for several columns."),
]  # fmt: skip
Reason = Annotated[str | None, Query(max_length=20, description="Only this reason code.")]


def _query(sort: str | None, feasible: bool | None, pareto: bool | None,
           ranges: list[str] | None, reason: str | None) -> DesignQuery:  # fmt: skip
    parsed = []
    for text in ranges or []:
        parts = text.split(":")
        if len(parts) != 3 or not parts[0]:
            raise parameter_error("query", "range", f"{text!r} is not key:low:high")
        try:
            low, high = (float(p) if p.strip() else None for p in parts[1:])
        except ValueError:
            raise parameter_error("query", "range", f"{text!r}: low and high are numbers") from None
        parsed.append((parts[0], low, high))
    return DesignQuery(sort, feasible, pareto, tuple(parsed), reason)


def _descriptions(api: ApiDep, process_id: str) -> dict[str, str]:
    definition = api.registry.get(process_id)
    if definition is None:
        return {}
    out = {}
    for entry in definition.result_paths:
        out[entry.path] = entry.description
    return out


def _columns(table: DesignTable, described: dict[str, str]) -> list[DesignColumnDocument]:
    def description(path: str) -> str:
        plain = path.split("|", 1)[0]
        return described.get(plain, described.get(plain.replace("[]", ""), ""))

    return [
        DesignColumnDocument(
            key=c.key,
            label=column_label(c),
            path=c.path,
            kind=c.kind,
            unit=c.unit,
            symbol=c.symbol,
            goal=c.goal,
            description=description(c.path),
        )
        for c in table.columns
    ]


@router.get(
    "/{job_id}/designs",
    summary="A design study's designs: paged, sorted and filtered",
    response_model=DesignPage,
)
async def get_designs(
    job_id: str,
    request: Request,
    api: ApiDep,
    limit: Annotated[int, Query(ge=1, le=1000)] = 100,
    cursor: Cursor = None,
    sort: Sort = None,
    feasible: Feasible = None,
    pareto: Pareto = None,
    ranges: Range = None,
    reason: Reason = None,
) -> DesignPage:
    query = _query(sort, feasible, pareto, ranges, reason)
    process_id, table = await run_in_threadpool(
        study_table, request.app.state.design_tables, api, job_id
    )
    try:
        page = await run_in_threadpool(design_page, table, query, limit, cursor)
    except DesignQueryError as exc:
        raise parameter_error("query", exc.parameter, str(exc)) from None
    here = [(k, v) for k, v in request.query_params.multi_items() if k != "cursor"]
    base = f"/v1/jobs/{job_id}/designs"
    links = [Link(href=f"{base}?{urlencode(request.query_params.multi_items())}".rstrip("?"),
                  rel="self", type="application/json")]  # fmt: skip
    if page["next_cursor"] is not None:
        href = f"{base}?{urlencode([*here, ('cursor', page['next_cursor'])])}"
        links.append(Link(href=href, rel="next", type="application/json"))
    described = _descriptions(api, process_id)
    rows: list[dict[str, Any]] = page["designs"]
    return DesignPage(jobID=job_id, process=process_id, total=page["total"],
                      matched=page["matched"], columns=_columns(table, described),
                      designs=[DesignRow(**row) for row in rows], links=links)  # fmt: skip


@router.get(
    "/{job_id}/designs/scatter",
    summary="Two columns of a design study's designs, as points or (beyond 10,000) bins",
    response_model=DesignScatter,
)
async def get_design_scatter(
    job_id: str,
    request: Request,
    api: ApiDep,
    x: Annotated[str, Query(pattern=_KEY, description="The column on x.")],
    y: Annotated[str, Query(pattern=_KEY, description="The column on y.")],
    feasible: Feasible = None,
    pareto: Pareto = None,
    ranges: Range = None,
    reason: Reason = None,
) -> DesignScatter:
    query = _query(None, feasible, pareto, ranges, reason)
    _, table = await run_in_threadpool(study_table, request.app.state.design_tables, api, job_id)
    try:
        answer = await run_in_threadpool(design_scatter, table, x, y, query)
    except DesignQueryError as exc:
        raise parameter_error("query", exc.parameter, str(exc)) from None
    return DesignScatter(jobID=job_id, **answer)


@router.get(
    "/{job_id}/designs/reasons",
    summary="A design study's infeasible designs grouped by reason, with counts",
    response_model=ReasonGroups,
)
def get_design_reasons(job_id: str, request: Request, api: ApiDep) -> ReasonGroups:
    """Reasons differing only in the numbers they quote are one group (from the
    study's ``infeasible_reasons``, which keeps its most frequent messages)."""
    study_table(request.app.state.design_tables, api, job_id)  # the caller's finished study
    result = api.store.get_result(job_id) or {}
    groups = reason_groups(result.get("infeasible_reasons") or [])
    return ReasonGroups(jobID=job_id, groups=[ReasonGroup(**g) for g in groups])
