"""A job submitted by a page's form: the same path as the API's execution
(:func:`worker.submission.submit`), its refusals turned into the problem document the
page shows beside the user's inputs (with ``Retry-After`` for a quota or a full queue).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from fastapi import Request
from fastapi.responses import HTMLResponse, RedirectResponse, Response
from starlette.concurrency import run_in_threadpool

from service.deps import Api
from service.documents import job_href
from service.errors import dexlab_problem
from service.problems import problem_document
from worker.errors import CostLimitExceeded, InvalidInputs, QueueFull, QuotaExceeded
from worker.submission import submit

__all__ = ["PageRefusal", "submit_from_page"]


@dataclass(frozen=True)
class PageRefusal:
    """Why a page's submission was refused: the ``problem`` document, and the
    ``Retry-After`` seconds of a quota or a full queue."""

    problem: dict[str, Any]
    retry_after: str | None = None

    @property
    def status(self) -> int:
        return int(self.problem["status"])

    def answered(self, page: HTMLResponse) -> HTMLResponse:
        """The page that shows the problem, with ``Retry-After`` when there is one."""
        if self.retry_after is not None:
            page.headers["Retry-After"] = self.retry_after
        return page


async def submit_from_page(
    request: Request, api: Api, process_id: str, inputs: dict[str, Any]
) -> Response | PageRefusal:
    """A 303 to the new job's page, or why the submission was refused."""
    try:
        job, _ = await run_in_threadpool(
            submit, api.store, api.registry, api.settings, process_id, inputs, None,
            api.dispatcher, api.identity.name,
        )  # fmt: skip
    except InvalidInputs as exc:
        return PageRefusal(problem_document("invalid-inputs", detail=exc.detail, errors=exc.errors))
    except CostLimitExceeded as exc:
        return PageRefusal(problem_document("cost-limit-exceeded", detail=exc.detail))
    except (QuotaExceeded, QueueFull) as exc:  # the page says so, with Retry-After
        answer = dexlab_problem(request, exc)
        return PageRefusal(json.loads(bytes(answer.body)), answer.headers.get("Retry-After"))
    return RedirectResponse(job_href(job.job_id), status_code=303)
