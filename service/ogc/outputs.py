"""A process's outputs, as OGC API - Processes names them.

Two kinds, one output ID each:

- every member of the job's result document (``ProcessDefinition.outputs``, plus the
  ``notes`` and ``paper_errata`` every job reports), a JSON value;
- every file a job of the process can write, named by its file name (the same name as
  ``/v1/jobs/{jobID}/results/{name}``), in one media type.

The files a process can write are declared by its family (``ProcessDefinition.files``)
and checked against real runs by the tests (tests/unit/service/test_ogc_outputs.py).  A
job need not write all of them (``"plots": false`` writes none of the figures).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from service.ogc.vocabulary import JSON
from worker.processes import ProcessDefinition

__all__ = ["OutputSpec", "process_outputs"]

_RUNNER_OUTPUTS: Mapping[str, str] = {
    "notes": "Remarks on the computation, in order; the paper's errata among them.",
    "paper_errata": "The notes that correct the paper (printed values that are wrong).",
}


@dataclass(frozen=True)
class OutputSpec:
    """One output: a result member (``artifact`` False, JSON) or a file."""

    id: str
    title: str
    description: str
    media_type: str
    artifact: bool

    def describe(self) -> dict[str, Any]:
        """The OGC output description (outputDescription.yaml)."""
        schema: dict[str, Any]
        if self.artifact:
            schema = {"type": "string", "contentMediaType": self.media_type}
            if self.media_type != "image/svg+xml" and not self.media_type.startswith("text/"):
                schema["contentEncoding"] = "binary"
        elif self.id in _RUNNER_OUTPUTS:
            schema = {"type": "array", "items": {"type": "string"}}
        else:
            schema = {}  # any JSON value: the result member's shape is in its description
        return {"title": self.title, "description": self.description, "schema": schema}


def process_outputs(definition: ProcessDefinition) -> dict[str, OutputSpec]:
    """Every output of ``definition``, by ID, in order: result members, then files."""
    outputs = {
        key: OutputSpec(key, key.replace("_", " "), text, JSON, artifact=False)
        for key, text in {**definition.outputs, **_RUNNER_OUTPUTS}.items()
    }
    for file in definition.files:
        description = f"{file.title}: a file of the job, as downloaded from its results."
        outputs[file.name] = OutputSpec(
            file.name, file.title, description, file.media_type, artifact=True
        )
    return outputs
