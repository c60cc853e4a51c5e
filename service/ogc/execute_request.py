"""The OGC execute request (execute.yaml): its model, and what it asks for.

``inputs`` maps each input ID to its value: in-line (a literal, an array, an object,
or a qualified value ``{"value": ..., "mediaType": "application/json"}``) or by
reference (``{"href": ...}``, fetched from an allowed host only).  ``outputs``
selects outputs and their ``transmissionMode`` (``value`` or ``reference``) and
``format``; omitted, every output the job produces is returned, result members by
value and files by reference.  ``response`` is ``raw`` (the default) or ``document``.
``subscriber`` names callback URIs (allowed hosts only, never silently ignored).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from service.ogc.outbound import OutboundPolicy
from service.ogc.outputs import OutputSpec
from service.ogc.vocabulary import JSON
from worker.errors import InvalidInputs

__all__ = [
    "InvalidRequest",
    "OgcExecuteRequest",
    "OgcOutputRequest",
    "OgcSubscriber",
    "Presentation",
    "presentation_of",
    "resolve_inputs",
    "subscriber_of",
]

_QUALIFIED_KEYS = frozenset({"value", "mediaType", "encoding", "schema"})
_LINK_KEYS = frozenset({"href", "rel", "type", "hreflang", "title"})
_URI = Field(None, min_length=1, max_length=2048)


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", populate_by_name=True)


class OgcOutputFormat(_Strict):
    mediaType: str | None = Field(None, max_length=255)
    encoding: str | None = Field(None, max_length=64)
    schema_: str | dict[str, Any] | None = Field(None, alias="schema")


class OgcOutputRequest(_Strict):
    """How one output is wanted."""

    format: OgcOutputFormat | None = None
    transmissionMode: Literal["value", "reference"] = "value"


class OgcSubscriber(_Strict):
    """URIs to call when the job starts (``inProgressUri``), succeeds or fails."""

    successUri: str = Field(..., min_length=1, max_length=2048)
    inProgressUri: str | None = _URI
    failedUri: str | None = _URI


class OgcExecuteRequest(_Strict):
    """The body of ``POST /ogc/processes/{processID}/execution`` (execute.yaml)."""

    inputs: dict[str, Any] = Field(
        default_factory=dict, description="Input ID -> value (see the process description)."
    )
    outputs: dict[str, OgcOutputRequest] | None = Field(
        None, description="The outputs wanted (default: all) and how each is sent."
    )
    response: Literal["raw", "document"] = Field(
        "raw", description="`raw`: the outputs as they are; `document`: a results document."
    )
    subscriber: OgcSubscriber | None = Field(
        None, description="Callback URIs (only hosts on the server's allow-list)."
    )
    retention_s: float | None = Field(
        None,
        gt=0,
        allow_inf_nan=False,
        strict=True,
        description="dexlab: keep the finished job and its results this many seconds "
        "(at most, and by default, the service's DEXLAB_RESULT_TTL_S).",
    )
    reuse: bool = Field(
        True,
        strict=True,
        description="dexlab: false computes afresh (as `Cache-Control: no-cache` does); "
        "true lets a stored result of the same inputs answer at once.",
    )
    share: bool = Field(
        True,
        strict=True,
        description="dexlab: false keeps this job's result from other API keys' jobs.",
    )


@dataclass(frozen=True)
class Presentation:
    """How the results are presented: ``response`` and the selected outputs with their
    transmission modes (None: every output the job has, by its default mode)."""

    response: str
    outputs: tuple[tuple[str, str], ...] | None

    def to_json(self) -> dict[str, Any]:
        outputs = None if self.outputs is None else [list(pair) for pair in self.outputs]
        return {"response": self.response, "outputs": outputs}

    @classmethod
    def from_json(cls, data: Mapping[str, Any] | None) -> Presentation:
        """The stored presentation; a job created without one (the native API) is
        presented as a document of every output."""
        if not data:
            return cls("document", None)
        outputs = data.get("outputs")
        return cls(
            str(data.get("response", "document")),
            None if outputs is None else tuple((str(i), str(m)) for i, m in outputs),
        )


class InvalidRequest(InvalidInputs):
    """The request asks for something the process cannot give (an output it does not
    have, a format, a callback the server will not send); ``errors`` names it."""


def _field_error(field: str, message: str) -> InvalidRequest:
    return InvalidRequest([{"field": field, "message": message, "type": "value_error"}])


def _input_error(field: str, message: str) -> InvalidInputs:
    return InvalidInputs([{"field": field, "message": message, "type": "value_error"}])


def _check_format(field: str, spec: OutputSpec, wanted: OgcOutputFormat | None) -> None:
    if wanted is None:
        return
    if wanted.mediaType is not None and wanted.mediaType.split(";")[0].strip() != spec.media_type:
        raise _field_error(
            f"{field}.format.mediaType",
            f"the output {spec.id!r} is only available as {spec.media_type}",
        )
    binary = spec.artifact and spec.media_type != "image/svg+xml" and spec.media_type != "text/csv"
    allowed = {None, "base64", "binary"} if binary else {None, "utf-8", "UTF-8"}
    if wanted.encoding not in allowed:
        raise _field_error(
            f"{field}.format.encoding",
            f"the output {spec.id!r} has no encoding {wanted.encoding!r}",
        )
    if wanted.schema_ is not None:
        raise _field_error(
            f"{field}.format.schema",
            "an output schema cannot be chosen; the process description gives each output's",
        )


def presentation_of(body: OgcExecuteRequest, outputs: Mapping[str, OutputSpec]) -> Presentation:
    """The presentation the request asks for; an unknown output, or a format the
    output does not have, is an error naming it."""
    if not body.outputs:
        return Presentation(body.response, None)
    selected = []
    for output_id, wanted in body.outputs.items():
        spec = outputs.get(output_id)
        if spec is None:
            raise _field_error(
                f"outputs.{output_id}",
                f"no output {output_id!r}; the process has: {', '.join(outputs)}",
            )
        _check_format(f"outputs.{output_id}", spec, wanted.format)
        selected.append((output_id, wanted.transmissionMode))
    return Presentation(body.response, tuple(selected))


def subscriber_of(body: OgcExecuteRequest, policy: OutboundPolicy) -> dict[str, str] | None:
    """The subscriber URIs, each checked against the allow-list; a URI that may not be
    called is an error naming it (a callback is never dropped silently)."""
    if body.subscriber is None:
        return None
    uris = body.subscriber.model_dump(exclude_none=True)
    for member, uri in uris.items():
        why = policy.refusal(uri)
        if why is not None:
            raise _field_error(f"subscriber.{member}", f"no callback can be sent there: {why}")
    return uris


def resolve_inputs(inputs: Mapping[str, Any], fetch: Callable[[str], Any]) -> dict[str, Any]:
    """The inputs as plain JSON values: qualified values unwrapped, references fetched
    with ``fetch(href)`` (which raises ValueError saying why it could not)."""
    resolved = {}
    for input_id, value in inputs.items():
        field = f"inputs.{input_id}"
        if isinstance(value, dict) and "value" in value and value.keys() <= _QUALIFIED_KEYS:
            media_type = value.get("mediaType")
            if media_type is not None and str(media_type).split(";")[0].strip() != JSON:
                raise _input_error(f"{field}.mediaType", "inputs are JSON: give application/json")
            value = value["value"]
        elif isinstance(value, dict) and "href" in value and value.keys() <= _LINK_KEYS:
            try:
                value = fetch(str(value["href"]))
            except ValueError as exc:
                raise _input_error(
                    f"{field}.href", f"the input could not be fetched: {exc}"
                ) from None
        resolved[input_id] = value
    return resolved
