"""Schemathesis against the real server's ``/openapi.json``: no 5xx, every answer as
documented.

The server runs with ``--workers 0`` so nothing executes (the property tests of each
family cover the worker side); every process has its own execute operation whose body
schema is that process's input model, so the generated requests cover each process's
own inputs.  Seeds are fixed (derandomized), so a run is repeatable; the cases add up
to more than 2,000 (the last test checks the count).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import schemathesis
from hypothesis import HealthCheck, Phase, given, settings
from schemathesis.checks import not_a_server_error
from schemathesis.generation import GenerationMode
from schemathesis.specs.openapi.checks import positive_data_acceptance

from tests.integration.servers import Deployment, deployment

pytestmark = [pytest.mark.integration, pytest.mark.slow]

#: Cases per operation (operations without parameters have fewer distinct cases).
EXAMPLES = 100
#: /health/ready answers 503 by design when no worker is up, as here.
NOT_READY_BY_DESIGN = "/health/ready"


@pytest.fixture(scope="module")
def api_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", Path(tmp_path_factory.mktemp("schemathesis")), workers=0) as dep:
        yield dep


def load_schema() -> Any:
    """The document the server serves (built from the same app factory, without a
    lifespan), so the operations can be parametrized at collection time."""
    from service.app import create_app
    from service.config import Settings

    return schemathesis.openapi.from_dict(create_app(Settings(workers=0)).openapi())


SCHEMA = load_schema()
OPERATIONS = {op.label: op for op in (r.ok() for r in SCHEMA.get_all_operations())}


def _negatable(label: str) -> bool:
    """Whether a request can be made invalid by its schema: a body or a query
    parameter (a free-text path parameter cannot be)."""
    definition = OPERATIONS[label].definition.raw
    parameters = definition.get("parameters", [])
    return "requestBody" in definition or any(p.get("in") == "query" for p in parameters)


CASES = [
    pytest.param(label, mode, id=f"{label}-{mode.value}")
    for label in sorted(OPERATIONS)
    for mode in (GenerationMode.POSITIVE, GenerationMode.NEGATIVE)
    if mode is GenerationMode.POSITIVE or _negatable(label)
]


@pytest.fixture(scope="module")
def case_counter() -> dict[str, int]:
    return {}


def test_the_served_document_is_the_one_tested(api_server: Deployment) -> None:
    served = api_server.client.get("/openapi.json").json()
    assert set(served["paths"]) == set(SCHEMA.raw_schema["paths"])


@pytest.mark.parametrize(("label", "mode"), CASES)
def test_every_answer_is_documented_and_none_is_a_server_error(
    label: str, mode: GenerationMode, api_server: Deployment, case_counter: dict[str, int]
) -> None:
    operation = OPERATIONS[label]

    @given(case=operation.as_strategy(generation_mode=mode))
    @settings(
        max_examples=EXAMPLES,
        derandomize=True,
        deadline=None,
        database=None,
        suppress_health_check=list(HealthCheck),
        # No shrinking: each step is a request; a failure is reported as found.
        phases=[Phase.explicit, Phase.reuse, Phase.generate],
    )
    def check(case: Any) -> None:
        # A wait would only hold the connection open: no worker runs here.
        if case.headers:
            case.headers = {k: v for k, v in case.headers.items() if k.lower() != "prefer"}
        response = case.call(base_url=api_server.base_url)
        case_counter[label] = case_counter.get(label, 0) + 1
        if case.path != NOT_READY_BY_DESIGN:
            assert response.status_code < 500, (response.status_code, response.text[:500])
        if response.status_code == 413:  # a body past DEXLAB_MAX_BODY_BYTES, refused unread
            assert response.json()["type"] == "/problems/request-too-large"
            return
        # Valid-by-schema inputs may still be refused: cross-field rules (a ratio
        # between links, a cost limit) are stated in descriptions and `x-` keywords,
        # which JSON Schema cannot check.
        case.validate_response(
            response, excluded_checks=[positive_data_acceptance, not_a_server_error]
        )
        assert response.headers.get("x-content-type-options") == ["nosniff"]

    check()


def test_enough_cases_ran(case_counter: dict[str, int]) -> None:
    """Runs after the parametrized tests (same module, file order)."""
    total = sum(case_counter.values())
    if total == 0:
        pytest.skip("the schemathesis cases did not run (deselected)")
    assert total >= 2000, case_counter
