"""Process summaries and OGC process descriptions, built from the registry.

A description's ``inputs`` map has one entry per property of the process's input
model: its title and description, ``minOccurs`` (1 when required, else 0),
``maxOccurs`` 1 (a list-valued input is one value, an array), and its JSON Schema made
self-contained (the model's ``$defs`` inlined) with the worked examples' values of
that input as ``examples``.  ``outputs`` is :func:`service.ogc.outputs.process_outputs`.
``result_paths``, an extension member, lists every number of the result with its unit
and symbol, as the process's own description does.
"""

from __future__ import annotations

import copy
import json
from collections.abc import Sequence
from typing import Any

from service.ogc.outputs import process_outputs
from service.ogc.schemas import OgcLink, OgcProcess, OgcProcessList, OgcProcessSummary
from service.ogc.urls import PublicUrls, self_and_alternate
from service.ogc.vocabulary import JSON, REL_EXECUTE, REL_PROCESSES
from worker.processes import ProcessDefinition

__all__ = ["inline_refs", "process_description", "process_list", "process_summary"]

#: Most worked-example values quoted per input.
_EXAMPLES_PER_INPUT = 3


def inline_refs(schema: dict[str, Any]) -> dict[str, Any]:
    """``schema`` with every local ``{"$ref": "#/$defs/Name"}`` replaced by the
    definition itself (recursively; sibling keywords kept), and ``$defs`` dropped.
    Raises ValueError on a reference it cannot resolve or a recursive definition."""
    definitions = schema.get("$defs", {})

    def resolve(node: Any, seen: tuple[str, ...]) -> Any:
        if isinstance(node, list):
            return [resolve(item, seen) for item in node]
        if not isinstance(node, dict):
            return node
        ref = node.get("$ref")
        if isinstance(ref, str):
            name = ref.removeprefix("#/$defs/")
            if name == ref or name not in definitions:
                raise ValueError(f"The schema reference {ref!r} is not a local definition.")
            if name in seen:
                raise ValueError(f"The schema definition {name!r} is recursive.")
            resolved = resolve(definitions[name], (*seen, name))
            siblings = {k: resolve(v, seen) for k, v in node.items() if k != "$ref"}
            return {**resolved, **siblings}
        return {k: resolve(v, seen) for k, v in node.items() if k != "$defs"}

    resolved: dict[str, Any] = resolve(copy.deepcopy(schema), ())
    return resolved


def _job_control(definition: ProcessDefinition) -> list[str]:
    modes = ["sync-execute", "async-execute"] if definition.sync_cost_limit else ["async-execute"]
    return [*modes, "dismiss"]


def process_summary(definition: ProcessDefinition, urls: PublicUrls) -> OgcProcessSummary:
    """processSummary.yaml: what the process is and how it can be run; links to its
    description, as JSON and as a page."""
    return OgcProcessSummary.model_validate(_summary(definition, urls))


def _summary(definition: ProcessDefinition, urls: PublicUrls) -> dict[str, Any]:
    href = urls.process(definition.id)
    return {
        "id": definition.id,
        "title": definition.title,
        "description": definition.description,
        "version": definition.version,
        "jobControlOptions": _job_control(definition),
        "outputTransmission": ["value", "reference"],
        "links": self_and_alternate(href, "the process description"),
    }


def _example_values(definition: ProcessDefinition, name: str) -> list[Any]:
    values: list[Any] = []
    seen: set[str] = set()
    for example in definition.examples:
        if name in example.inputs:
            key = json.dumps(example.inputs[name], sort_keys=True)
            if key not in seen and len(values) < _EXAMPLES_PER_INPUT:
                seen.add(key)
                values.append(copy.deepcopy(example.inputs[name]))
    return values


def _inputs(definition: ProcessDefinition) -> dict[str, Any]:
    schema = inline_refs(definition.inputs_schema)
    required = set(schema.get("required", ()))
    inputs = {}
    for name, property_schema in schema.get("properties", {}).items():
        input_schema = dict(property_schema)
        title = input_schema.pop("title", name)
        description = input_schema.pop("description", "")
        examples = _example_values(definition, name)
        if examples:
            input_schema["examples"] = examples
        inputs[name] = {
            "title": title,
            "description": description,
            "minOccurs": 1 if name in required else 0,
            "maxOccurs": 1,
            "schema": input_schema,
        }
    return inputs


def process_description(definition: ProcessDefinition, urls: PublicUrls) -> OgcProcess:
    """process.yaml: the summary, the ``inputs`` and ``outputs`` maps, and links to
    running it, to the method it follows and to the process list."""
    document = _summary(definition, urls)
    document["inputs"] = _inputs(definition)
    document["outputs"] = {
        output_id: spec.describe() for output_id, spec in process_outputs(definition).items()
    }
    document["result_paths"] = definition.describe()["result_paths"]
    links = document["links"]
    links.append(
        {
            "href": f"{urls.process(definition.id)}/execution",
            "rel": REL_EXECUTE,
            "type": JSON,
            "title": "POST an execute request to run it",
        }
    )
    if definition.method_doc:
        links.append(
            {
                "href": f"{urls.root}/methods/{definition.method_doc}",
                "rel": "describedby",
                "type": "text/html",
                "title": "The method, its equations and the paper's errata",
            }
        )
    links.append(
        {
            "href": f"{urls.ogc}/processes",
            "rel": REL_PROCESSES,
            "type": JSON,
            "title": "all processes",
        }
    )
    return OgcProcess.model_validate(document)


def process_list(
    definitions: Sequence[ProcessDefinition], urls: PublicUrls, limit: int, offset: int
) -> tuple[list[ProcessDefinition], OgcProcessList]:
    """processList.yaml: the page of ``limit`` summaries from ``offset`` (and the
    definitions on it), with a ``next`` link while more follow."""
    page = list(definitions[offset : offset + limit])
    links = self_and_alternate(
        f"{urls.ogc}/processes?limit={limit}&offset={offset}", "this page of processes"
    )
    if offset + limit < len(definitions):
        links.append(
            {
                "href": f"{urls.ogc}/processes?limit={limit}&offset={offset + limit}",
                "rel": "next",
                "type": JSON,
                "title": "the next page",
            }
        )
    return page, OgcProcessList(
        processes=[process_summary(d, urls) for d in page],
        links=[OgcLink.model_validate(link) for link in links],
    )
