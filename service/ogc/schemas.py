"""The façade's documents as pydantic models (OGC 18-062r2's schemas, as dexlab fills
them); and the problem statuses of each route.

The builders (:mod:`service.ogc.landing`, :mod:`service.ogc.process_documents`,
:mod:`service.ogc.jobs.documents`) return these models, and each JSON route declares
its model as ``response_model``: FastAPI publishes it and serializes the answer with it
(``response_model_exclude_unset``: a time not reached yet stays absent).  The results
(:mod:`service.ogc.results`) take the form the execute request chose, so they are
described by :data:`RESULTS_SCHEMA` and :data:`ARTIFACT_CONTENT` instead.  Names carry
an ``Ogc`` prefix: the native API has its own ``Link``, ``JobList`` and so on.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field
from pydantic.json_schema import SkipJsonSchema

__all__ = [
    "ARTIFACT_CONTENT",
    "OGC_ROUTE_PROBLEMS",
    "RESULTS_SCHEMA",
    "OgcConfClasses",
    "OgcJobList",
    "OgcLandingPage",
    "OgcProcess",
    "OgcProcessList",
    "OgcStatusInfo",
]


class _Document(BaseModel):
    model_config = ConfigDict(extra="forbid")


class OgcLink(_Document):
    href: str
    rel: str
    type: str | SkipJsonSchema[None] = None
    title: str | SkipJsonSchema[None] = None


class OgcLandingPage(_Document):
    """landingPage.yaml."""

    title: str
    description: str
    links: list[OgcLink]


class OgcConfClasses(_Document):
    """confClasses.yaml: the conformance classes met."""

    conformsTo: list[str]


JobControl = Literal["sync-execute", "async-execute", "dismiss"]


class OgcProcessSummary(_Document):
    """processSummary.yaml."""

    id: str
    title: str
    description: str
    version: str
    jobControlOptions: list[JobControl]
    outputTransmission: list[Literal["value", "reference"]]
    links: list[OgcLink]


class OgcProcessList(_Document):
    """processList.yaml."""

    processes: list[OgcProcessSummary]
    links: list[OgcLink]


class OgcInputDescription(_Document):
    """inputDescription.yaml."""

    model_config = ConfigDict(extra="forbid", populate_by_name=True)

    title: str
    description: str
    minOccurs: int = Field(ge=0)
    maxOccurs: int | Literal["unbounded"]
    schema_: dict[str, Any] = Field(alias="schema")


class OgcOutputDescription(_Document):
    """outputDescription.yaml."""

    model_config = ConfigDict(extra="forbid", populate_by_name=True)

    title: str
    description: str
    schema_: dict[str, Any] = Field(alias="schema")


class OgcResultPath(_Document):
    """An extension member of dexlab's: one number of the result, with its unit and
    symbol (as ``result_paths`` of ``GET /v1/processes/{processID}``)."""

    path: str
    unit: str
    symbol: str
    description: str
    kernel: bool = False


class OgcProcess(OgcProcessSummary):
    """process.yaml: the summary with the inputs and outputs maps (and, an extension,
    ``result_paths``: every number of the result with its unit)."""

    inputs: dict[str, OgcInputDescription]
    outputs: dict[str, OgcOutputDescription]
    result_paths: list[OgcResultPath]


class OgcStatusInfo(_Document):
    """statusInfo.yaml (a time not reached yet is left out)."""

    processID: str
    type: Literal["process"]
    jobID: str
    status: Literal["accepted", "running", "successful", "failed", "dismissed"]
    message: str
    progress: int = Field(ge=0, le=100)
    created: str
    updated: str
    started: str | SkipJsonSchema[None] = None
    finished: str | SkipJsonSchema[None] = None
    expires: str | SkipJsonSchema[None] = Field(
        None,
        description="dexlab: when the finished job and its results are deleted (absent "
        "while it is unfinished); statusInfo.yaml allows members it does not list.",
    )
    reused_from: str | bool | SkipJsonSchema[None] = Field(
        None,
        description="dexlab: a job answered at once by a stored result of the same result "
        "key: the ID of the job that computed it when that job was the caller's (or the "
        "caller is an admin), else true; absent for a job that computed its own result.",
    )
    links: list[OgcLink]


class OgcJobList(_Document):
    """jobList.yaml: a page of jobs, newest first."""

    jobs: list[OgcStatusInfo]
    links: list[OgcLink]


#: results.yaml (``response=document``): output ID -> an in-line value, a qualified value
#: or a link; with ``response=raw`` and one output, that output's own JSON value.
RESULTS_SCHEMA: dict[str, Any] = {
    "title": "OgcResults",
    "description": "response=document: an object, output ID -> its value in line (a "
    'literal or array; an object as a qualified value {"value", "mediaType"}; a file as '
    '{"value": base64, "encoding": "base64", "mediaType"}) or by reference ({"href", '
    '"type", "title"}).  response=raw with one JSON output: that output\'s value.',
}

#: What a raw output can be: JSON, or a file's bytes.
ARTIFACT_CONTENT: dict[str, Any] = {
    media: {"schema": {"type": "string", "format": "binary"}}
    for media in (
        "image/png",
        "image/svg+xml",
        "text/csv",
        "application/x-npz",
        "multipart/related",
    )
}

#: Problem statuses of each route (see service.openapi).
OGC_ROUTE_PROBLEMS: dict[tuple[str, str], tuple[int, ...]] = {
    # A 400: a bad query, path or header parameter (``f`` on every GET), or a POST's
    # malformed body.
    ("get", "/ogc"): (400,),
    ("get", "/ogc/"): (400,),
    ("get", "/ogc/conformance"): (400,),
    ("get", "/ogc/processes"): (400,),
    ("get", "/ogc/processes/{processID}"): (400, 404),
    ("post", "/ogc/processes/{processID}/execution"): (400, 404, 413, 422, 429, 503, 507),
    ("get", "/ogc/jobs"): (400, 403, 503),
    # An expired job (its retention ended) is 410 for a while, then 404.
    ("get", "/ogc/jobs/{jobID}"): (400, 404, 410, 503),
    ("delete", "/ogc/jobs/{jobID}"): (404, 410, 503),
    ("get", "/ogc/jobs/{jobID}/results"): (400, 404, 410, 503, 507),
    ("get", "/ogc/jobs/{jobID}/results/{outputID}"): (400, 404, 410, 503, 507),
}


def document_process_ids(document: dict[str, Any], process_ids: list[str]) -> None:
    """Name the registered processes in the OpenAPI document's ``processID`` filter of
    ``GET /ogc/jobs`` (another ID is a bad value: ``400 invalid-parameter-value``)."""
    operation = document.get("paths", {}).get("/ogc/jobs", {}).get("get", {})
    for parameter in operation.get("parameters", []):
        if parameter.get("name") == "processID" and parameter.get("in") == "query":
            for option in parameter["schema"].get("anyOf", [parameter["schema"]]):
                if option.get("type") == "array":
                    option["items"] = {"type": "string", "enum": list(process_ids)}
