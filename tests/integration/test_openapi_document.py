"""The real server's ``/openapi.json``: a valid OpenAPI document whose worked examples
are the registry's, each valid against its operation's request schema.

That every worked example runs to ``successful`` is proved by
tests/integration/test_families.py (``test_worked_example_runs_to_success``, one real
run of each).  Running them all a second time here would double the suite's longest
part, so this module asserts instead that the examples in ``/openapi.json`` are exactly
the inputs that suite runs: the same processes, the same number of examples, and, by
index, the same inputs as the process description it takes them from.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest
from jsonschema import Draft202012Validator
from openapi_spec_validator import OpenAPIV31SpecValidator, validate
from referencing import Registry, Resource
from referencing.jsonschema import DRAFT202012

from service.routes.process_operations import family_tag
from tests.integration.servers import Deployment, deployment
from tests.integration.test_families import EXAMPLES as FAMILY_SUITE_EXAMPLES
from worker.registry import default_registry

REGISTRY = default_registry()

pytestmark = pytest.mark.integration

DOCUMENT_URI = "urn:dexlab:openapi"
PROCESSES = list(default_registry())
CASES = [pytest.param(d.id, i, id=f"{d.id}-{i}") for d in PROCESSES for i in range(len(d.examples))]


@pytest.fixture(scope="module")
def api(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("openapi"), workers=0) as dep:
        yield dep


@pytest.fixture(scope="module")
def document(api: Deployment) -> dict[str, Any]:
    r = api.client.get("/openapi.json")
    assert r.status_code == 200 and r.headers["content-type"] == "application/json"
    body: dict[str, Any] = r.json()
    return body


def execute_operation(document: dict[str, Any], process_id: str) -> dict[str, Any]:
    operation: dict[str, Any] = document["paths"][f"/v1/processes/{process_id}/execution"]["post"]
    return operation


def request_validator(document: dict[str, Any], process_id: str) -> Draft202012Validator:
    """A JSON Schema 2020-12 validator of the operation's request body, resolving the
    document's ``$ref``s (OpenAPI 3.1 schemas are JSON Schema 2020-12)."""
    resource = Resource.from_contents(document, default_specification=DRAFT202012)
    registry: Registry[Any] = Registry().with_resource(DOCUMENT_URI, resource)
    path = f"/v1/processes/{process_id}/execution".replace("~", "~0").replace("/", "~1")
    pointer = f"/paths/{path}/post/requestBody/content/application~1json/schema"
    return Draft202012Validator(
        {"$ref": f"{DOCUMENT_URI}#{pointer}"},
        registry=registry,
        format_checker=Draft202012Validator.FORMAT_CHECKER,
    )


def test_document_is_valid_openapi_3_1(document: dict[str, Any]) -> None:
    assert document["openapi"].startswith("3.1.")
    validate(document, cls=OpenAPIV31SpecValidator)


def test_each_process_has_its_operation_under_its_family_tag(document: dict[str, Any]) -> None:
    documented = {
        path.split("/")[3]
        for path in document["paths"]
        if path.startswith("/v1/processes/") and path.endswith("/execution")
        and "{" not in path
    }  # fmt: skip
    assert documented == {d.id for d in PROCESSES}
    tags = [t["name"] for t in document["tags"]]
    for definition in PROCESSES:
        operation = execute_operation(document, definition.id)
        assert operation["tags"] == [family_tag(REGISTRY, definition)], definition.id
        assert family_tag(REGISTRY, definition) in tags


def test_examples_are_those_the_families_suite_runs(
    api: Deployment, document: dict[str, Any]
) -> None:
    """Per process: the OpenAPI examples, in order, are the registry's and the process
    description's (which test_families.py runs by index); and that suite's cases are
    exactly one per OpenAPI example."""
    openapi_cases: set[tuple[str, int]] = set()
    for definition in PROCESSES:
        content = execute_operation(document, definition.id)["requestBody"]["content"]
        examples = list(content["application/json"]["examples"].values())
        assert [e["value"] for e in examples] == [
            {"inputs": dict(ex.inputs)} for ex in definition.examples
        ], definition.id
        assert all(
            ex.title in e["summary"] for ex, e in zip(definition.examples, examples, strict=True)
        )
        described = api.client.get(f"/v1/processes/{definition.id}").json()["examples"]
        assert [{"inputs": d["inputs"]} for d in described] == [e["value"] for e in examples]
        openapi_cases |= {(definition.id, i) for i in range(len(examples))}
    suite_cases = {tuple(p.values) for p in FAMILY_SUITE_EXAMPLES}
    assert suite_cases == openapi_cases
    assert len(openapi_cases) >= len(PROCESSES)


@pytest.mark.parametrize(("process_id", "index"), CASES)
def test_example_validates_against_its_request_schema(
    document: dict[str, Any], process_id: str, index: int
) -> None:
    content = execute_operation(document, process_id)["requestBody"]["content"]
    example = list(content["application/json"]["examples"].values())[index]["value"]
    validator = request_validator(document, process_id)
    errors = [f"{list(e.absolute_path)}: {e.message}" for e in validator.iter_errors(example)]
    assert not errors, errors
    # The schema is the real contract, not an open object: it refuses what the API refuses.
    assert not validator.is_valid({"inputs": {**example["inputs"], "no_such_input": 1}})
    assert not validator.is_valid({})


def test_the_schema_is_the_process_input_model(document: dict[str, Any]) -> None:
    """Each operation's ``inputs`` schema is its process's input model (its members,
    the required ones, closed to others)."""
    for definition in PROCESSES:
        content = execute_operation(document, definition.id)["requestBody"]["content"]
        ref = content["application/json"]["schema"]["properties"]["inputs"]["$ref"]
        published = document["components"]["schemas"][ref.removeprefix("#/components/schemas/")]
        own = definition.inputs_model.model_json_schema()
        assert published["title"] == own["title"], definition.id
        assert published["properties"].keys() == own["properties"].keys(), definition.id
        assert published.get("required") == own.get("required"), definition.id
        assert published["additionalProperties"] is False, definition.id
