"""The live explorer of a process with a preview (:mod:`worker.previews`):
``GET /pages/processes/{processID}/explore`` (not in the OpenAPI document).

A slider and a number box per design field, starting from the process's worked example
(:attr:`~worker.previews.ProcessPreview.start_example`, with the preview's overrides);
``explorer.js`` posts each change to ``/pages/processes/{id}/preview`` (a newer change
cancels the request of an older one) and redraws the heat maps (Plotly, vendored) and
the indices.  "Run as a job" posts the current design to the process's run form (then
the job's page), at the worked example's resolution and with its plots; "Add to
comparison" runs it as a job too and keeps its ID for ``/pages/compare``.  Without
JavaScript the page says the explorer needs it and links the process's forms.
"""

from __future__ import annotations

import json
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse

from service.deps import ApiDep
from service.routes.previews import CSRF_HEADER
from worker.preview_run import preview_definition
from worker.processes import ProcessDefinition

__all__ = ["explorer_context", "field_value", "router"]

router = APIRouter(prefix="/pages", include_in_schema=False)


def field_value(inputs: Any, path: str) -> Any:
    """The value at a dotted ``path`` of ``inputs`` (``links.1``: ``inputs["links"][1]``);
    None where there is none."""
    value = inputs
    for part in path.split("."):
        if isinstance(value, dict):
            value = value.get(part)
        elif isinstance(value, list | tuple) and part.isdigit() and int(part) < len(value):
            value = value[int(part)]
        else:
            return None
    return value


def explorer_context(definition: ProcessDefinition) -> dict[str, Any]:
    """What explore.html draws: the sliders (each with its start value) and the
    explorer's configuration for its script (JSON)."""
    spec = definition.preview
    assert spec is not None  # preview_definition checked it
    example = definition.examples[spec.start_example]
    start = spec.start_inputs(example.inputs)
    fields = [{**field.describe(), "value": field_value(start, field.path)}
              for field in spec.fields]  # fmt: skip
    config = {
        "process_id": definition.id,
        "preview_url": f"/pages/processes/{definition.id}/preview",
        "csrf_header": CSRF_HEADER,
        "inputs": start,
        "fields": fields,
        # what a job of the current design takes from the worked example instead of
        # the explorer's start (its resolution, its plots): null = the input's default
        "job_restores": {key: example.inputs.get(key) for key in spec.start_overrides},
    }
    return {
        "process": definition,
        "example_title": example.title,
        "fields": fields,
        "config_json": json.dumps(config).replace("</", "<\\/"),
    }


@router.get("/processes/{process_id}/explore")
def explore(process_id: str, request: Request, api: ApiDep) -> HTMLResponse:
    definition = preview_definition(api.registry, process_id)
    return api.pages.render(request, "explore.html", explorer_context(definition))
