"""Where the service is and how to read its answers (no I/O: both clients use it).

:class:`Connection` holds the service URL, the API key, the per-request timeout and the
retry policy; :func:`read_answer` turns a response into its JSON document or raises the
exception its problem document names (:mod:`dexlab.errors`).
"""

from __future__ import annotations

import json
import os
import uuid
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib.metadata import PackageNotFoundError, version
from typing import Any
from urllib.parse import quote

import httpx

from dexlab.errors import DexlabError, ServiceUnreachable, error_from_problem, retry_after_seconds
from dexlab.retry import RetryPolicy

__all__ = [
    "DEFAULT_URL",
    "Connection",
    "api_path",
    "error_from_response",
    "json_object",
    "new_idempotency_key",
    "problem_of",
    "read_answer",
    "read_bytes",
    "unreachable",
]

DEFAULT_URL = "http://127.0.0.1:8000"


def _client_version() -> str:
    try:
        return version("dexlab")
    except PackageNotFoundError:  # a source tree without an install
        return "unknown"


@dataclass(frozen=True)
class Connection:
    """The service a client talks to.

    ``url`` defaults to ``DEXLAB_URL`` (else ``http://127.0.0.1:8000``), ``api_key`` to
    ``DEXLAB_API_KEY`` (sent as ``Authorization: Bearer``; none when empty); ``timeout``
    bounds each request in seconds (a job's wait has its own ``timeout``).
    """

    url: str
    api_key: str | None = field(default=None, repr=False)
    timeout: float = 30.0
    retry: RetryPolicy = field(default_factory=RetryPolicy)

    @classmethod
    def resolve(
        cls,
        url: str | None = None,
        api_key: str | None = None,
        timeout: float = 30.0,
        retry: RetryPolicy | None = None,
    ) -> Connection:
        """A connection from the arguments, falling back on the environment."""
        base = (url or os.environ.get("DEXLAB_URL") or DEFAULT_URL).strip()
        if not base.startswith(("http://", "https://")):
            raise ValueError(f"The 'url' of a dexlab service must start with http:// or "
                             f"https://. Got {base!r} instead.")  # fmt: skip
        if not timeout > 0:
            raise ValueError(
                f"The 'timeout' must be a positive number of seconds. Got {timeout!r}."
            )
        key = api_key if api_key is not None else os.environ.get("DEXLAB_API_KEY")
        return cls(base.rstrip("/"), key or None, timeout, retry or RetryPolicy())

    def headers(self) -> dict[str, str]:
        """The headers of every request."""
        headers = {"Accept": "application/json", "User-Agent": f"dexlab-python/{_client_version()}"}
        if self.api_key:
            headers["Authorization"] = f"Bearer {self.api_key}"
        return headers


def api_path(*segments: str) -> str:
    """``/v1/<segment>/...`` with each segment quoted whole (an ID can hold no ``/``)."""
    return "/v1/" + "/".join(quote(str(s), safe="") for s in segments)


def new_idempotency_key() -> str:
    """A fresh ``Idempotency-Key`` for one submission (kept across its retries)."""
    return f"dexlab-client-{uuid.uuid4().hex}"


def problem_of(response: httpx.Response) -> dict[str, Any] | None:
    """The response's JSON object body, if it has one (a problem document on errors)."""
    try:
        body = json.loads(response.content)
    except (ValueError, UnicodeDecodeError):
        return None
    return body if isinstance(body, dict) else None


def error_from_response(response: httpx.Response) -> DexlabError:
    """The exception for an error response (a problem document, or a bare error page)."""
    problem = problem_of(response)
    if problem is None or not ({"type", "title", "detail"} & problem.keys()):
        text = " ".join(response.text.split())[:300] if response.content else ""
        problem = {
            "type": "about:blank",
            "title": response.reason_phrase or f"HTTP {response.status_code}",
            "status": response.status_code,
            "detail": text
            or f"{response.request.method} {response.request.url} answered {response.status_code}.",
        }
    retry_after = retry_after_seconds(response.headers.get("Retry-After"), problem)
    return error_from_problem(response.status_code, problem, retry_after=retry_after)


def read_answer(response: httpx.Response) -> Any:
    """A successful response's JSON document; an error response raises."""
    if response.status_code >= 400:
        raise error_from_response(response)
    try:
        return json.loads(response.content)
    except (ValueError, UnicodeDecodeError) as exc:
        raise DexlabError(
            {"title": "Not a dexlab answer", "detail": f"{response.request.url} answered "
             f"{response.status_code} with a body that is not JSON."},
            status=response.status_code,
        ) from exc  # fmt: skip


def read_bytes(response: httpx.Response) -> bytes:
    """A successful response's bytes; an error response raises."""
    if response.status_code >= 400:
        raise error_from_response(response)
    return response.content


def unreachable(url: str, error: BaseException) -> ServiceUnreachable:
    """The error for a service that did not answer after every retry."""
    reason = str(error) or type(error).__name__
    return ServiceUnreachable(
        {"type": "about:blank", "title": "Service unreachable",
         "detail": f"Cannot reach the dexlab service at {url} ({reason})."},
    )  # fmt: skip


def json_object(value: Any, what: str) -> Mapping[str, Any]:
    """``value`` if it is a JSON object; a :class:`DexlabError` naming ``what`` if not."""
    if not isinstance(value, Mapping):
        raise DexlabError(
            {"title": "Not a dexlab answer", "detail": f"{what} is not a JSON object."}
        )
    return value
