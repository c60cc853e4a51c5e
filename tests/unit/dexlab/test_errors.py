"""Problem documents -> the client's typed exceptions (dexlab.errors, dexlab.connection)."""

from __future__ import annotations

from datetime import UTC, datetime, timedelta
from email.utils import format_datetime
from typing import Any

import httpx
import pytest

from dexlab import (
    CostLimitExceeded,
    DexlabError,
    IdempotencyConflict,
    InvalidInputs,
    JobDismissed,
    JobFailed,
    NoSuchArtifact,
    NoSuchJob,
    NoSuchProcess,
    NotFound,
    QuotaExceeded,
    RequestRefused,
    ResultNotReady,
    ServiceUnavailable,
    Unauthorized,
)
from dexlab.connection import error_from_response, read_answer
from dexlab.errors import error_from_problem, retry_after_seconds

OGC = "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0"


def problem(slug: str, status: int, **extra: Any) -> dict[str, Any]:
    return {"type": f"/problems/{slug}", "title": slug, "status": status, "detail": "d", **extra}


@pytest.mark.parametrize(
    ("doc", "status", "kind"),
    [
        (problem("invalid-inputs", 422), 422, InvalidInputs),
        (problem("invalid-request", 422), 422, InvalidInputs),
        (problem("cost-limit-exceeded", 422), 422, CostLimitExceeded),
        (problem("idempotency-conflict", 422), 422, IdempotencyConflict),
        (problem("unauthorized", 401), 401, Unauthorized),
        (problem("quota-exceeded", 429), 429, QuotaExceeded),
        (problem("no-such-process", 404), 404, NoSuchProcess),
        (problem("no-such-job", 404), 404, NoSuchJob),
        (problem("no-such-artifact", 404), 404, NoSuchArtifact),
        (problem("not-found", 404), 404, NotFound),
        (problem("result-not-ready", 404), 404, ResultNotReady),
        (problem("job-dismissed", 410), 410, JobDismissed),
        (problem("store-unavailable", 503), 503, ServiceUnavailable),
        (problem("storage-full", 507), 507, ServiceUnavailable),
        # OGC's exception types end in the same slugs.
        ({"type": f"{OGC}/no-such-job", "title": "x", "status": 404}, 404, NoSuchJob),
        ({"type": f"{OGC}/result-not-ready", "title": "x"}, 404, ResultNotReady),
        # A bad parameter under /ogc/: the service's 400 (service.problems).
        ({"type": f"{OGC}/invalid-parameter-value", "status": 400}, 400, InvalidInputs),
        # A failed job's results: its failure's own type and status, naming the job.
        (problem("time-limit-exceeded", 500, jobID="j1"), 500, JobFailed),
        (problem("storage-error", 503, jobID="j1"), 503, JobFailed),
        # Unknown types fall back on the status, then on the base class.
        (problem("brand-new-thing", 401), 401, Unauthorized),
        (problem("brand-new-thing", 429), 429, QuotaExceeded),
        (problem("internal-error", 500), 500, DexlabError),
    ],
)
def test_each_problem_type_raises_its_exception(
    doc: dict[str, Any], status: int, kind: type[DexlabError]
) -> None:
    error = error_from_problem(status, doc)
    assert type(error) is kind
    assert error.status == status and error.problem["type"] == doc["type"]


def test_the_hierarchy_groups_refusals_and_lookups() -> None:
    for kind in (
        InvalidInputs,
        CostLimitExceeded,
        IdempotencyConflict,
        Unauthorized,
        QuotaExceeded,
    ):
        assert issubclass(kind, RequestRefused)
    for kind in (NoSuchProcess, NoSuchJob, NoSuchArtifact):
        assert issubclass(kind, NotFound)
    assert not issubclass(ResultNotReady, NotFound)


def test_invalid_inputs_carry_every_field_error() -> None:
    errors = [
        {"field": "inputs.lengths", "message": "needs four", "type": "value_error"},
        {"field": "inputs.ground", "message": "Field required", "type": "missing"},
    ]
    error = error_from_problem(422, problem("invalid-inputs", 422, errors=errors))
    assert isinstance(error, InvalidInputs)
    assert [e["field"] for e in error.errors] == ["inputs.lengths", "inputs.ground"]
    assert str(error) == "invalid-inputs: d"


def test_cost_limit_carries_the_cost_and_the_limit() -> None:
    doc = problem("cost-limit-exceeded", 422, cost=14_414_403_600, cost_limit=3_000_000_000)
    error = error_from_problem(422, doc)
    assert isinstance(error, CostLimitExceeded)
    assert error.cost == 14_414_403_600 and error.cost_limit == 3_000_000_000


def test_job_failed_names_the_job() -> None:
    error = error_from_problem(500, problem("job-error", 500, jobID="abc"))
    assert isinstance(error, JobFailed) and error.job_id == "abc" and error.slug == "job-error"


def test_retry_after_from_seconds_a_date_or_the_problem() -> None:
    assert retry_after_seconds("7") == 7.0
    later = format_datetime(datetime.now(UTC) + timedelta(seconds=30), usegmt=True)
    assert 25 <= (retry_after_seconds(later) or 0) <= 30
    assert retry_after_seconds(None, {"retry_after": 12}) == 12.0
    assert retry_after_seconds(None, {"retry_after_s": 3.5}) == 3.5
    assert retry_after_seconds("soon") is None and retry_after_seconds(None, {}) is None
    assert retry_after_seconds(None, {"retry_after": True}) is None


def response(status: int, body: bytes, content_type: str, **headers: str) -> httpx.Response:
    request = httpx.Request("GET", "http://dexlab.test/v1/jobs/x")
    return httpx.Response(
        status, content=body, headers={"content-type": content_type, **headers}, request=request
    )


def test_a_quota_response_carries_retry_after_from_its_header() -> None:
    body = b'{"type": "/problems/quota-exceeded", "title": "Quota exceeded", "status": 429}'
    error = error_from_response(
        response(429, body, "application/problem+json", **{"Retry-After": "9"})
    )
    assert isinstance(error, QuotaExceeded) and error.retry_after == 9.0


def test_an_error_page_that_is_not_a_problem_still_raises_by_status() -> None:
    error = error_from_response(response(503, b"<html>Bad gateway</html>", "text/html"))
    assert isinstance(error, ServiceUnavailable)
    assert error.detail == "<html>Bad gateway</html>" and error.type == "about:blank"


def test_a_success_that_is_not_json_is_an_error() -> None:
    with pytest.raises(DexlabError, match="not JSON"):
        read_answer(response(200, b"<html/>", "text/html"))
