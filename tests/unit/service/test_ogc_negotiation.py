"""The OGC façade's request parsing: Prefer and the execution mode, the job-list
``datetime`` and filters, the execute request's inputs, outputs and subscriber."""

from __future__ import annotations

from datetime import UTC, datetime, timedelta, timezone

import pytest

from service.ogc.execute_request import (
    InvalidRequest,
    OgcExecuteRequest,
    Presentation,
    presentation_of,
    resolve_inputs,
    subscriber_of,
)
from service.ogc.execution_mode import Preferences, execution_mode, parse_prefer
from service.ogc.jobs.query import listing_filter, page_query, parse_datetime_interval
from service.ogc.outbound import OutboundPolicy
from service.ogc.outputs import process_outputs
from service.preferences import MAX_WAIT_S
from worker.contract import JobStatus
from worker.errors import InvalidInputs
from worker.registry import default_registry


@pytest.mark.parametrize(
    ("header", "expected"),
    [
        (None, Preferences()),
        ("respond-async", Preferences(respond_async=True)),
        ("Respond-Sync", Preferences(respond_sync=True)),
        ("respond-sync, wait=5", Preferences(respond_sync=True, wait_s=5.0)),
        ('wait="2.5"; x=y', Preferences(wait_s=2.5)),
        ("wait=0, wait=-3, wait=nan, wait=soon", Preferences()),
        ("return=minimal, handling=lenient", Preferences()),
    ],
)
def test_prefer_header(header: str | None, expected: Preferences) -> None:
    assert parse_prefer(header) == expected


def test_execution_mode_follows_the_standard() -> None:
    # No preference, a process that runs both ways: synchronous, capped wait, no header.
    mode = execution_mode(Preferences(), can_run_sync=True)
    assert (mode.synchronous, mode.wait_s, mode.applied_if_sync) == (True, MAX_WAIT_S, None)
    # respond-async is honoured, and said so.
    mode = execution_mode(Preferences(respond_async=True, wait_s=9), can_run_sync=True)
    assert (mode.synchronous, mode.applied_if_async) == (False, "respond-async")
    # respond-sync and wait are honoured where the request may run synchronously ...
    mode = execution_mode(Preferences(respond_sync=True, wait_s=1e9), can_run_sync=True)
    assert (mode.synchronous, mode.wait_s) == (True, MAX_WAIT_S)
    assert mode.applied_if_sync == f"respond-sync, wait={MAX_WAIT_S:g}"
    # ... and not where it may not (async only, or above the sync cost limit).
    mode = execution_mode(Preferences(respond_sync=True), can_run_sync=False)
    assert (mode.synchronous, mode.applied_if_sync, mode.applied_if_async) == (False, None, None)


def test_datetime_instants_and_intervals() -> None:
    t = datetime(2024, 5, 4, 10, 13, tzinfo=UTC)
    assert parse_datetime_interval("2024-05-04T10:13:00Z") == (t, t)
    assert parse_datetime_interval("2024-05-04t10:13:00z") == (t, t)
    plus5 = datetime(2024, 5, 4, 15, 13, tzinfo=timezone(timedelta(hours=5)))
    assert parse_datetime_interval("2024-05-04T15:13:00+05:00")[0] == plus5 == t
    assert parse_datetime_interval("../2024-05-04T10:13:00Z") == (None, t)
    assert parse_datetime_interval("/2024-05-04T10:13:00Z") == (None, t)
    assert parse_datetime_interval("2024-05-04T10:13:00Z/..") == (t, None)
    assert parse_datetime_interval("2024-05-04T10:13:00Z/") == (t, None)
    later = parse_datetime_interval("2024-05-04T10:13:00Z/2024-05-05T00:00:00.5Z")
    assert later == (t, datetime(2024, 5, 5, 0, 0, 0, 500000, tzinfo=UTC))


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("2024-05-04", "RFC 3339"),
        ("2024-05-04T10:13:00", "time zone"),
        ("2024-13-04T10:13:00Z", "not a valid date-time"),
        ("../..", "at least one end"),
        ("2024-05-05T00:00:00Z/2024-05-04T00:00:00Z", "ends before it starts"),
        ("2024-05-04T10:13:00Z/2024-05-05T10:13:00Z/..", "one interval"),
    ],
)
def test_bad_datetimes_say_why(text: str, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        parse_datetime_interval(text)


def test_listing_filter_and_page_query() -> None:
    where = listing_filter(["a", "b"], [JobStatus.RUNNING], ["process"], None, 3, None)
    assert where.process_ids == {"a", "b"} and where.statuses == {JobStatus.RUNNING}
    assert where.min_duration_s == 3 and where.max_duration_s is None
    assert listing_filter(None, None, ["other"], None, None, None).statuses == frozenset()
    assert listing_filter(None, None, None, None, None, None).statuses is None
    query = page_query([("status", "running"), ("cursor", "old"), ("status", "failed")], "new")
    assert query == "status=running&status=failed&cursor=new"


FOURBAR = default_registry().get("fourbar-grashof")
assert FOURBAR is not None
OUTPUTS = process_outputs(FOURBAR)


def test_outputs_selection_and_formats() -> None:
    body = OgcExecuteRequest.model_validate(
        {
            "outputs": {
                "grashof": {},
                "fourbar_motion.svg": {
                    "transmissionMode": "reference",
                    "format": {"mediaType": "image/svg+xml"},
                },
            },
            "response": "document",
        }
    )
    assert presentation_of(body, OUTPUTS) == Presentation(
        "document", (("grashof", "value"), ("fourbar_motion.svg", "reference"))
    )
    assert presentation_of(OgcExecuteRequest(), OUTPUTS) == Presentation("raw", None)
    with pytest.raises(InvalidRequest, match="no output 'nope'") as unknown:
        presentation_of(OgcExecuteRequest.model_validate({"outputs": {"nope": {}}}), OUTPUTS)
    assert unknown.value.errors[0]["field"] == "outputs.nope"
    wrong = {"outputs": {"fourbar_motion.png": {"format": {"mediaType": "image/svg+xml"}}}}
    with pytest.raises(InvalidRequest, match="only available as image/png") as media:
        presentation_of(OgcExecuteRequest.model_validate(wrong), OUTPUTS)
    assert media.value.errors[0]["field"] == "outputs.fourbar_motion.png.format.mediaType"
    schema = {"outputs": {"grashof": {"format": {"schema": "https://example.org/s.json"}}}}
    with pytest.raises(InvalidRequest, match="cannot be chosen"):
        presentation_of(OgcExecuteRequest.model_validate(schema), OUTPUTS)


def test_presentation_roundtrip_and_native_default() -> None:
    presentation = Presentation("raw", (("grashof", "reference"),))
    assert Presentation.from_json(presentation.to_json()) == presentation
    assert Presentation.from_json(None) == Presentation("document", None)


def test_qualified_values_unwrap_and_references_are_fetched() -> None:
    fetched: list[str] = []

    def fetch(href: str) -> object:
        fetched.append(href)
        return [1, 2, 3, 4]

    inputs = {
        "lengths": {"href": "http://data.example/lengths.json", "type": "application/json"},
        "ground": {"value": 1, "mediaType": "application/json"},
        "plots": False,
    }
    assert resolve_inputs(inputs, fetch) == {"lengths": [1, 2, 3, 4], "ground": 1, "plots": False}
    assert fetched == ["http://data.example/lengths.json"]
    with pytest.raises(InvalidInputs, match="inputs are JSON") as media:
        resolve_inputs({"ground": {"value": "1", "mediaType": "text/plain"}}, fetch)
    assert media.value.errors[0]["field"] == "inputs.ground.mediaType"

    def refuse(href: str) -> object:
        raise ValueError("not on the allow-list")

    with pytest.raises(InvalidInputs, match="could not be fetched: not on the allow-list") as ref:
        resolve_inputs({"lengths": {"href": "http://x/"}}, refuse)
    assert ref.value.errors[0]["field"] == "inputs.lengths.href"


def test_subscribers_are_refused_unless_allowed() -> None:
    body = OgcExecuteRequest.model_validate(
        {
            "subscriber": {
                "successUri": "http://hooks.example:8080/done",
                "failedUri": "http://169.254.169.254/latest",
            }
        }
    )
    with pytest.raises(InvalidRequest, match="DEXLAB_OUTBOUND_ALLOW_HOSTS") as off:
        subscriber_of(body, OutboundPolicy.from_setting(""))
    assert off.value.errors[0]["field"] == "subscriber.successUri"
    policy = OutboundPolicy.from_setting("hooks.example:8080")
    with pytest.raises(InvalidRequest, match=r"169\.254\.169\.254:80 is not on") as other:
        subscriber_of(body, policy)
    assert other.value.errors[0]["field"] == "subscriber.failedUri"
    allowed = OgcExecuteRequest.model_validate(
        {"subscriber": {"successUri": "http://hooks.example:8080/done"}}
    )
    assert subscriber_of(allowed, policy) == {"successUri": "http://hooks.example:8080/done"}
    assert subscriber_of(OgcExecuteRequest(), policy) is None


@pytest.mark.parametrize(
    ("setting", "uri", "allowed"),
    [
        ("hooks.example", "https://hooks.example/x", True),
        ("hooks.example", "http://HOOKS.example:9999/x", True),
        ("hooks.example:443", "https://hooks.example/x", True),
        ("hooks.example:443", "http://hooks.example/x", False),
        ("hooks.example", "http://evil.example/x", False),
        ("hooks.example", "ftp://hooks.example/x", False),
        ("hooks.example", "http://user:pw@hooks.example/x", False),
        ("hooks.example", "/relative", False),
        ("127.0.0.1:8123, hooks.example", "http://127.0.0.1:8123/cb", True),
    ],
)
def test_outbound_allow_list(setting: str, uri: str, allowed: bool) -> None:
    assert (OutboundPolicy.from_setting(setting).refusal(uri) is None) is allowed


@pytest.mark.parametrize("entry", ["http://x/", "x:notaport", "a b", "x/path", "u@x"])
def test_outbound_setting_rejects_bad_entries(entry: str) -> None:
    with pytest.raises(ValueError, match="'outbound_allow_hosts' setting"):
        OutboundPolicy.from_setting(entry)
