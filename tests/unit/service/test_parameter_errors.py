"""Every query and path parameter of every ``/v1`` and ``/ogc`` route, sent a bad value,
answers its surface's one shape (issue 27): ``/v1`` a 422 ``/problems/invalid-request``
naming ``query.<name>`` (or ``path.<name>``), ``/ogc`` a 400 of OGC's
``invalid-parameter-value`` type (OWS ``InvalidParameterValue``) naming it the
same way.

The parameters are read from the served OpenAPI document, so a new parameter is tested
the day it is published.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from service.ogc.vocabulary import INVALID_PARAMETER_VALUE

pytestmark = pytest.mark.anyio

#: Values no schema can make valid, per parameter, beyond those the schema implies.
EXTRA_BAD: dict[str, tuple[str, ...]] = {
    "cursor": ("garbage",),
    "datetime": ("yesterday",),
}


def _resolve(schema: dict[str, Any], components: dict[str, Any]) -> dict[str, Any]:
    if "$ref" in schema:
        return dict(components[schema["$ref"].rsplit("/", 1)[1]])
    return schema


def bad_values(schema: dict[str, Any], components: dict[str, Any]) -> list[str]:
    """Values the schema refuses (none for an unconstrained string)."""
    schema = _resolve(schema, components)
    if "anyOf" in schema:
        found: list[str] = []
        for option in schema["anyOf"]:
            if option.get("type") != "null":
                found += bad_values(option, components)
        return found
    kind = schema.get("type")
    if kind == "array":
        return bad_values(schema["items"], components)
    if "enum" in schema or "const" in schema:
        return ["not-one-of-these"]
    if kind == "integer":
        return ["not-a-number", str(schema.get("maximum", 10**12) + 1)]
    if kind == "string" and "maxLength" in schema:
        return ["a" * (schema["maxLength"] + 1)]
    return []


def parameter_cases(document: dict[str, Any]) -> Iterator[tuple[str, str, str, str, str]]:
    """(method, url, location, name, bad value) for every constrained parameter."""
    components = document["components"]["schemas"]
    for template, operations in document["paths"].items():
        if not template.startswith(("/v1", "/ogc")):
            continue
        for method, operation in operations.items():
            parameters = [
                p for p in operation.get("parameters", []) if p["in"] in ("query", "path")
            ]
            for parameter in parameters:
                name, where = parameter["name"], parameter["in"]
                values = bad_values(parameter.get("schema", {}), components)
                values += list(EXTRA_BAD.get(name, ()))
                for value in values:
                    url = template
                    for other in parameters:
                        if other["in"] == "path":
                            filler = value if other is parameter else "x"
                            url = url.replace("{" + other["name"] + "}", filler)
                    query = {name: value} if where == "query" else {}
                    yield (
                        method.upper(),
                        url + ("?" + httpx.QueryParams(query).__str__() if query else ""),
                        where,
                        name,
                        value,
                    )


async def test_every_parameter_error_has_its_surfaces_shape(client: httpx.AsyncClient) -> None:
    document = (await client.get("/openapi.json")).json()
    cases = list(parameter_cases(document))
    assert len(cases) > 30, cases  # the enumeration found the parameters
    names = {(url.split("?")[0].split("/")[1], name) for _, url, _, name, _ in cases}
    assert {("v1", "cursor"), ("v1", "limit"), ("ogc", "cursor"), ("ogc", "limit")} <= names
    wrong = []
    for method, url, where, name, _value in cases:
        r = await client.request(method, url)
        body = r.json() if r.headers.get("content-type", "").endswith("json") else {}
        fields = [e.get("field", "") for e in body.get("errors", [])]
        named = any(f == f"{where}.{name}" or f.startswith(f"{where}.{name}[") for f in fields)
        if url.startswith("/v1"):
            shape = (422, "/problems/invalid-request")
        else:
            shape = (400, INVALID_PARAMETER_VALUE)
        got = (r.status_code, body.get("type"))
        ok = got == shape and named and r.headers["content-type"] == "application/problem+json"
        if not ok:
            wrong.append((method, url[:80], got, fields))
    assert not wrong, "\n".join(map(str, wrong))


def test_no_such_process_is_worded_in_one_place() -> None:
    root = Path(__file__).resolve().parents[3]
    wording = [
        str(path.relative_to(root))
        for package in ("service", "worker")
        for path in (root / package).rglob("*.py")
        if 'f"No process {' in path.read_text()
    ]
    assert wording == ["worker/errors.py"]
