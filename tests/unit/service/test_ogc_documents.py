"""OGC process summaries and descriptions built from the registry, and status info."""

from __future__ import annotations

import json
from datetime import UTC, datetime

import jsonschema
import pytest

from service.documents import as_json
from service.ogc.jobs.documents import job_list, status_info
from service.ogc.process_documents import inline_refs, process_description, process_summary
from service.ogc.schemas import OgcJobList, OgcProcess, OgcProcessSummary, OgcStatusInfo
from service.ogc.urls import PublicUrls
from service.ogc.vocabulary import REL_EXCEPTIONS, REL_EXECUTE, REL_PROCESSES, REL_RESULTS
from worker.contract import JobRecord, JobStatus
from worker.processes import ProcessDefinition
from worker.registry import default_registry

URLS = PublicUrls("https://dexlab.example.org/kin")
DEFINITIONS = list(default_registry())


@pytest.mark.parametrize("definition", DEFINITIONS, ids=lambda d: d.id)
def test_descriptions_map_every_input_with_a_self_contained_schema(
    definition: ProcessDefinition,
) -> None:
    document = as_json(process_description(definition, URLS))
    OgcProcess.model_validate(document)  # the documented shape, nothing more
    schema = definition.inputs_schema
    assert set(document["inputs"]) == set(schema["properties"])
    required = set(schema.get("required", ()))
    for name, entry in document["inputs"].items():
        assert entry["minOccurs"] == (1 if name in required else 0) and entry["maxOccurs"] == 1
        assert entry["title"] and "$ref" not in json.dumps(entry["schema"])
        jsonschema.Draft202012Validator.check_schema(entry["schema"])
    # Every worked example's value of each input validates against that input's schema.
    for example in definition.examples:
        for name, value in example.inputs.items():
            jsonschema.validate(value, document["inputs"][name]["schema"])
    rels = {link["rel"]: link for link in document["links"]}
    assert rels["self"]["href"] == f"https://dexlab.example.org/kin/ogc/processes/{definition.id}"
    assert rels[REL_EXECUTE]["href"].endswith(f"/ogc/processes/{definition.id}/execution")
    assert rels["describedby"] == {
        "href": f"https://dexlab.example.org/kin/methods/{definition.method_doc}",
        "rel": "describedby",
        "type": "text/html",
        "title": "The method, its equations and the paper's errata",
    }
    assert rels[REL_PROCESSES]["href"] == "https://dexlab.example.org/kin/ogc/processes"
    assert {"notes", "paper_errata", *definition.outputs} <= set(document["outputs"])
    # dexlab's extension: every number of the result with its unit, as /v1 describes it
    assert document["result_paths"] == definition.describe()["result_paths"]
    assert document["result_paths"] and all(
        set(entry) - {"kernel"} == {"path", "unit", "symbol", "description"}
        for entry in document["result_paths"]
    )


def test_summaries_say_how_each_process_runs() -> None:
    modes = {}
    for definition in DEFINITIONS:
        summary = as_json(process_summary(definition, URLS))
        OgcProcessSummary.model_validate(summary)
        assert summary["outputTransmission"] == ["value", "reference"]
        modes[definition.id] = summary["jobControlOptions"]
    assert modes["fourbar-grashof"] == ["sync-execute", "async-execute", "dismiss"]
    assert modes["planar3r-synthesis"] == ["async-execute", "dismiss"]  # no sync limit


def test_inline_refs_resolves_nested_definitions_and_refuses_cycles() -> None:
    schema = {
        "$defs": {
            "A": {"type": "object", "properties": {"b": {"$ref": "#/$defs/B"}}},
            "B": {"type": "integer"},
        },
        "properties": {"a": {"$ref": "#/$defs/A", "description": "kept"}},
    }
    assert inline_refs(schema) == {
        "properties": {
            "a": {"type": "object", "properties": {"b": {"type": "integer"}}, "description": "kept"}
        },
    }
    with pytest.raises(ValueError, match="recursive"):
        inline_refs(
            {"$defs": {"A": {"items": {"$ref": "#/$defs/A"}}}, "items": {"$ref": "#/$defs/A"}}
        )
    with pytest.raises(ValueError, match="not a local definition"):
        inline_refs({"items": {"$ref": "https://example.org/s.json"}})


def job(status: JobStatus, **kw: object) -> JobRecord:
    t = datetime(2024, 5, 4, 10, 13, tzinfo=UTC)
    return JobRecord(
        job_id="j1",
        process_id="fourbar-grashof",
        status=status,
        inputs={},
        created=t,
        updated=t,
        **kw,
    )  # type: ignore[arg-type]


def test_status_info_links_and_times() -> None:
    queued = as_json(status_info(job(JobStatus.ACCEPTED), URLS))
    OgcStatusInfo.model_validate(queued)
    assert queued["created"] == "2024-05-04T10:13:00Z" and "started" not in queued
    assert [link["rel"] for link in queued["links"]] == ["self", "alternate", "up", "describedby"]
    assert queued["links"][0]["href"] == "https://dexlab.example.org/kin/ogc/jobs/j1"
    assert queued["links"][1]["href"] == "https://dexlab.example.org/kin/ogc/jobs/j1?f=html"
    assert queued["links"][1]["type"] == "text/html"
    done = as_json(
        status_info(
            job(
                JobStatus.SUCCESSFUL,
                progress=100.0,
                started=datetime(2024, 5, 4, 10, 14, tzinfo=UTC),
                finished=datetime(2024, 5, 4, 10, 15, tzinfo=UTC),
            ),
            URLS,
        )
    )
    assert (done["started"], done["finished"]) == ("2024-05-04T10:14:00Z", "2024-05-04T10:15:00Z")
    assert done["links"][-1] == {
        "href": "https://dexlab.example.org/kin/ogc/jobs/j1/results",
        "rel": REL_RESULTS,
        "type": "application/json",
        "title": "the job's results",
    }
    failed = as_json(status_info(job(JobStatus.FAILED), URLS))
    assert failed["links"][-1]["rel"] == REL_EXCEPTIONS
    page = as_json(
        job_list([job(JobStatus.RUNNING)], URLS, f"{URLS.ogc}/jobs", f"{URLS.ogc}/jobs?cursor=x")
    )
    OgcJobList.model_validate(page)
    assert [link["rel"] for link in page["links"]] == ["self", "alternate", "next"]
