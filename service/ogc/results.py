"""A finished job's outputs, presented as its execute request asked (18-062r2, 7.11.4
and 7.13): a results document, one raw output, ``multipart/related``, or ``204`` with
``Link`` headers.

======== ============================ ==============================================
response outputs                      answer
======== ============================ ==============================================
document any                          200 ``application/json``, results.yaml: output
                                      ID -> in-line value (objects as qualified
                                      values, files base64) or ``{"href", "type"}``
raw      one, by value                200, the output itself in its media type
raw      all by reference             204, one ``Link`` header per output
raw      several, by value or mixed   200 ``multipart/related`` (RFC 2387), one part
                                      per output, ``Content-ID`` = the output ID;
                                      by reference: an empty part with
                                      ``Content-Location``
======== ============================ ==============================================

A result member that is null has no value to give: a document leaves it out.  Files
are streamed from the store (bounded memory, base64 in a document).
"""

from __future__ import annotations

import base64
import json
import uuid
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from starlette.responses import JSONResponse, Response, StreamingResponse

from service.documents import artifact_headers
from service.ogc.execute_request import Presentation
from service.ogc.outputs import OutputSpec
from service.ogc.urls import PublicUrls
from service.ogc.vocabulary import JSON, REL_RESULTS
from worker.contract import JobRecord
from worker.errors import NoSuchArtifact
from worker.store.base import JobStore, StoredArtifact

__all__ = ["SelectedOutput", "document_bytes", "results_response", "select_outputs"]

#: Bytes read per base64 step (a multiple of 3, so chunks encode independently).
_B64_STEP = 3 * 256 * 1024


@dataclass(frozen=True)
class SelectedOutput:
    """An output to present: a result member's ``value``, or a file (``stored``)."""

    spec: OutputSpec
    mode: str
    value: Any = None
    stored: StoredArtifact | None = None

    def href(self, urls: PublicUrls, job_id: str) -> str:
        if self.spec.artifact:
            return urls.artifact(job_id, self.spec.id)
        return urls.output(job_id, self.spec.id)


def select_outputs(
    job: JobRecord,
    result: Mapping[str, Any],
    outputs: Mapping[str, OutputSpec],
    presentation: Presentation,
    store: JobStore,
) -> list[SelectedOutput]:
    """The outputs to present, in order.  By default every output the job has (result
    members by value, files by reference); a requested output the job did not produce
    (a figure of a job run without plots) is left out."""
    files = {a.name for a in job.artifacts}
    if presentation.outputs is None:
        wanted = [
            (output_id, "reference" if spec.artifact else "value")
            for output_id, spec in outputs.items()
            if (output_id in files if spec.artifact else output_id in result)
        ]
    else:
        wanted = list(presentation.outputs)
    selected = []
    for output_id, mode in wanted:
        spec = outputs.get(output_id)
        if spec is None:
            continue
        if spec.artifact:
            stored = store.artifact(job.job_id, output_id) if output_id in files else None
            if stored is not None:
                selected.append(SelectedOutput(spec, mode, stored=stored))
        elif output_id in result:
            selected.append(SelectedOutput(spec, mode, value=result[output_id]))
    return selected


def _file_chunks(store: JobStore, job_id: str, stored: StoredArtifact) -> Iterator[bytes]:
    yield from store.artifact_chunks(job_id, stored)


def _base64_chunks(chunks: Iterator[bytes]) -> Iterator[bytes]:
    """Base64 of the concatenated chunks, in pieces (each cut at a multiple of 3 bytes,
    so the pieces join into one valid encoding)."""
    pending = b""
    for chunk in chunks:
        pending += chunk
        if len(pending) >= _B64_STEP:
            cut = len(pending) - len(pending) % 3
            yield base64.b64encode(pending[:cut])
            pending = pending[cut:]
    if pending:
        yield base64.b64encode(pending)


def _inline(value: Any) -> Any:
    """A result member as results.yaml holds it: objects as qualified values."""
    if isinstance(value, dict):
        return {"value": value, "mediaType": JSON}
    return value


def _document_chunks(
    selected: list[SelectedOutput], urls: PublicUrls, job_id: str, store: JobStore
) -> Iterator[bytes]:
    yield b"{"
    first = True
    for output in selected:
        if not output.spec.artifact and output.mode == "value" and output.value is None:
            continue  # null has no in-line form in results.yaml
        yield (b"" if first else b",") + json.dumps(output.spec.id).encode() + b":"
        first = False
        if output.mode == "reference":
            link = {
                "href": output.href(urls, job_id),
                "type": output.spec.media_type,
                "title": output.spec.title,
            }
            yield json.dumps(link).encode()
        elif output.stored is not None:
            yield b'{"value":"'
            yield from _base64_chunks(_file_chunks(store, job_id, output.stored))
            tail = {"encoding": "base64", "mediaType": output.spec.media_type}
            yield b'",' + json.dumps(tail)[1:].encode()
        else:
            yield json.dumps(_inline(output.value), allow_nan=False).encode()
    yield b"}"


def document_bytes(
    selected: list[SelectedOutput], urls: PublicUrls, job_id: str, store: JobStore
) -> bytes:
    """The results document in memory (for outputs sent by reference or small)."""
    return b"".join(_document_chunks(selected, urls, job_id, store))


def _link_header(output: SelectedOutput, urls: PublicUrls, job_id: str) -> str:
    return (
        f'<{output.href(urls, job_id)}>; rel="{REL_RESULTS}"; '
        f'type="{output.spec.media_type}"; title="{output.spec.id}"'
    )


def _multipart_chunks(
    selected: list[SelectedOutput],
    urls: PublicUrls,
    job_id: str,
    store: JobStore,
    boundary: str,
) -> Iterator[bytes]:
    for output in selected:
        headers = [f"Content-ID: {output.spec.id}"]
        if output.mode == "reference":
            headers.append(f"Content-Location: {output.href(urls, job_id)}")
        else:
            headers.append(f"Content-Type: {output.spec.media_type}")
        head = "".join(f"{line}\r\n" for line in headers)
        yield f"--{boundary}\r\n{head}\r\n".encode()
        if output.mode == "value":
            if output.stored is not None:
                yield from _file_chunks(store, job_id, output.stored)
            else:
                yield json.dumps(output.value, allow_nan=False).encode()
        yield b"\r\n"
    yield f"--{boundary}--\r\n".encode()


def results_response(
    job: JobRecord,
    selected: list[SelectedOutput],
    presentation: Presentation,
    urls: PublicUrls,
    store: JobStore,
    headers: Mapping[str, str] | None = None,
) -> Response:
    """The answer presenting ``selected`` of a successful ``job`` (see the table)."""
    extra = dict(headers or {})
    job_id = job.job_id
    if presentation.response == "document":
        chunks = _document_chunks(selected, urls, job_id, store)
        return StreamingResponse(chunks, media_type=JSON, headers=extra)
    if selected and all(o.mode == "reference" for o in selected):
        links = ", ".join(_link_header(o, urls, job_id) for o in selected)
        return Response(status_code=204, headers={**extra, "Link": links})
    if len(selected) == 1:
        (output,) = selected
        if output.stored is not None:
            file_headers = {**artifact_headers(output.stored), **extra}
            file_headers["Content-Length"] = str(output.stored.info.size)
            chunks = _file_chunks(store, job_id, output.stored)
            return StreamingResponse(
                chunks, media_type=output.spec.media_type, headers=file_headers
            )
        return JSONResponse(output.value, headers=extra)
    if not selected:
        raise NoSuchArtifact(
            f"Job {job_id} produced none of the outputs asked for (a job run without plots "
            "has no figures)."
        )
    boundary = uuid.uuid4().hex
    first_type = (
        "application/octet-stream"
        if selected[0].mode == "reference"
        else (selected[0].spec.media_type)
    )
    media_type = f'multipart/related; boundary="{boundary}"; type="{first_type}"'
    chunks = _multipart_chunks(selected, urls, job_id, store, boundary)
    return StreamingResponse(chunks, media_type=media_type, headers=extra)
