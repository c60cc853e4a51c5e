"""A family says who it is, and the service reads it: a family made up here, registered
the way the shipped ones are (:func:`worker.registry.build_registry`), is listed under
its own tag in the OpenAPI document and on the processes page, its worked examples
cite its paper, and no module of the service names it."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import httpx
import pytest
from pydantic import BaseModel, ConfigDict, Field

from tests.unit.service.asgi_app import asgi_client
from worker.contract import JobContext, JobOutcome
from worker.processes import FamilyInfo, ProcessDefinition, ProcessExample
from worker.registry import build_registry, default_registry, family_packages

pytestmark = pytest.mark.anyio

ROOT = Path(__file__).resolve().parents[3]


class CountInputs(BaseModel):
    """Inputs of the made-up process."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    n: int = Field(1, ge=1, le=3, description="How many.")


def run_count(inputs: CountInputs, ctx: JobContext) -> JobOutcome:
    return JobOutcome(result={"n": inputs.n})


COUNT = ProcessDefinition(
    id="toy-count",
    title="Toy mechanisms: a count",
    description="Counts to n (a process made up by a test).",
    inputs_model=CountInputs,
    run=run_count,
    examples=(ProcessExample("Count to two", {"n": 2}),),
    outputs={"n": "The count."},
    cost=lambda inputs: inputs.n,
    cost_limit=3,
)
TOY = SimpleNamespace(
    FAMILY=FamilyInfo(
        name="toy_mechanisms",
        tag="Toy mechanisms",
        description="A family made up by a test.",
        paper="Nobody 2026",
    ),
    PROCESSES=(COUNT,),
)


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    registry = build_registry((*family_packages(), TOY))
    async with asgi_client(tmp_path, registry) as c:
        yield c


async def test_a_new_family_has_its_own_tag_in_the_openapi_document(
    client: httpx.AsyncClient,
) -> None:
    document: dict[str, Any] = (await client.get("/openapi.json")).json()
    tags = {tag["name"]: tag["description"] for tag in document["tags"]}
    assert tags["Toy mechanisms"] == "A family made up by a test."
    operation = document["paths"]["/v1/processes/toy-count/execution"]["post"]
    assert operation["tags"] == ["Toy mechanisms"]
    examples = operation["requestBody"]["content"]["application/json"]["examples"]
    assert [e["summary"] for e in examples.values()] == ["Nobody 2026: Count to two"]
    # the shipped families keep theirs, and the design study stays with the processes
    for family in default_registry().families():
        assert family.tag in tags
    study = document["paths"]["/v1/processes/design-study/execution"]["post"]
    assert study["tags"] == ["processes"]


async def test_a_new_family_has_its_own_section_on_the_processes_page(
    client: httpx.AsyncClient,
) -> None:
    listed = (await client.get("/v1/processes")).json()
    assert "toy-count" in [p["id"] for p in listed["processes"]]
    page = await client.get("/v1/processes", headers={"Accept": "text/html"})
    assert page.status_code == 200
    assert '<h2 id="family-toy_mechanisms">Toy mechanisms</h2>' in page.text
    assert "A family made up by a test." in page.text


def test_the_service_names_no_family() -> None:
    """Tags, descriptions and papers come from the families, not from the service."""
    named = []
    for family in default_registry().families():
        for path in sorted((ROOT / "service").rglob("*.py")):
            text = path.read_text()
            if family.tag in text or family.paper in text:
                named.append((str(path.relative_to(ROOT)), family.name))
    assert not named, named
