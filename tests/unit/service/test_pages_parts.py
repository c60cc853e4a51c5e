"""The pieces of the browser pages: negotiation, the inputs table, the result tables,
the method pages, the form origin check."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from starlette.exceptions import HTTPException
from starlette.requests import Request

from service.pages.forms import check_form_origin
from service.pages.input_table import input_rows, unit_of
from service.pages.method_docs import MethodDocs, default_docs_dir
from service.pages.negotiation import prefers_html, wants_html
from service.pages.result_view import ResultNode, format_scalar, result_view
from service.pages.views import compact_json
from worker.registry import default_registry

BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,image/avif,*/*;q=0.8"


def request(
    method: str = "GET", path: str = "/", query: str = "", headers: dict[str, str] | None = None
) -> Request:
    raw = [(k.lower().encode(), v.encode()) for k, v in (headers or {}).items()]
    return Request(
        {
            "type": "http",
            "method": method,
            "path": path,
            "query_string": query.encode(),
            "headers": raw,
        }
    )


@pytest.mark.parametrize(
    ("accept", "html"),
    [
        (None, False),
        ("", False),
        ("*/*", False),
        ("application/json", False),
        ("application/problem+json", False),
        (BROWSER, True),
        ("text/html", True),
        ("text/*", True),
        ("text/html;q=0.5, application/json", False),
        ("application/json;q=0.5, text/html", True),
        ("text/html;q=0.8, */*;q=0.8", False),
        ("text/html;q=0, */*", False),
        ("text/html;q=oops, application/json;q=0.1", False),  # a malformed range is skipped
        ("garbage", False),
    ],
)
def test_accept_header(accept: str | None, html: bool) -> None:
    assert prefers_html(accept) is html


@pytest.mark.parametrize(
    ("method", "path", "query", "accept", "html"),
    [
        ("GET", "/v1/jobs", "f=html", None, True),
        ("GET", "/v1/jobs", "f=json", BROWSER, False),
        ("GET", "/v1/jobs", "", BROWSER, True),
        ("GET", "/v1/jobs", "f=xml", BROWSER, False),
        ("HEAD", "/", "", BROWSER, True),
        ("POST", "/v1/processes/x/execution", "f=html", BROWSER, False),
        ("DELETE", "/v1/jobs/x", "", BROWSER, False),
        ("POST", "/pages/jobs/x/dismiss", "", None, True),
    ],
)
def test_wants_html(method: str, path: str, query: str, accept: str | None, html: bool) -> None:
    headers = {"accept": accept} if accept else {}
    assert wants_html(request(method, path, query, headers)) is html


@pytest.mark.parametrize(
    ("headers", "allowed"),
    [
        ({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:8000"}, True),
        ({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:8001"}, False),
        ({"host": "dexlab.test", "origin": "https://evil.test"}, False),
        ({"host": "dexlab.test", "origin": "null"}, False),
        ({"host": "dexlab.test"}, False),
        ({"host": "dexlab.test", "sec-fetch-site": "same-origin"}, True),
        (
            {"host": "dexlab.test", "sec-fetch-site": "cross-site", "origin": "http://dexlab.test"},
            False,
        ),
        ({"host": "dexlab.test", "sec-fetch-site": "same-site"}, False),
    ],
)
def test_form_origin_check(headers: dict[str, str], allowed: bool) -> None:
    check = request("POST", "/pages/jobs/x/dismiss", headers=headers)
    if allowed:
        check_form_origin(check)
    else:
        with pytest.raises(HTTPException, match="own pages") as raised:
            check_form_origin(check)
        assert raised.value.status_code == 403


def test_units_from_keywords_and_names() -> None:
    assert unit_of("l1", {"type": "number", "x-unit": "length"}) == "length units"
    assert unit_of("l2", {"anyOf": [{"type": "number", "x-unit": "mm"}, {"type": "null"}]}) == "mm"
    assert unit_of("tilt_max_deg", {"type": "number"}) == "deg"
    assert unit_of("time_limit_s", {"type": "number"}) == "s"
    assert unit_of("samples", {"type": "integer"}) == ""


def schema_of(process_id: str) -> dict[str, Any]:
    definition = default_registry().get(process_id)
    assert definition is not None
    return definition.inputs_schema


def test_inputs_table_resolves_refs_unions_and_items() -> None:
    by_name = {r.name: r for r in input_rows(schema_of("planar3r-synthesis"))}
    assert by_name["l3"].required and by_name["l3"].unit == "length (length_unit)"
    assert by_name["l3"].range == "1e-6 ≤ x ≤ 1e6"
    assert by_name["grid"].type == "object"
    assert (
        by_name["grid.points_per_axis"].default == "201"
        and by_name["grid.points_per_axis"].depth == 1
    )
    assert by_name["joint_limits_deg"].type == "[3 × [2 × number]] or null"
    assert by_name["joint_limits_deg"].unit == "deg"
    assert by_name["trajectory"].type == "PolylineTrajectory or PolynomialTrajectory or null"
    assert by_name["trajectory (PolynomialTrajectory).x_end"].required
    assert "matches" in by_name["length_unit"].range
    chains = {r.name: r for r in input_rows(schema_of("chain-parallelism"))}
    assert chains["chains[] (LoopChain).lengths"].range.startswith("3–8 items")
    assert "longest ≤ 1e6 × shortest" in chains["chains[] (LoopChain).lengths"].range
    assert chains["chains[] (MultiLoopChain).links"].type == "map of name → number or PolygonalLink"


def test_every_process_input_has_a_row() -> None:
    for definition in default_registry():
        rows = {r.name for r in input_rows(definition.inputs_schema)}
        assert set(definition.inputs_schema["properties"]) <= rows, definition.id
        assert all(r.type for r in input_rows(definition.inputs_schema)), definition.id


def walk(node: ResultNode) -> list[ResultNode]:
    children = (
        [c for _, c in node.entries] + [c for row in node.rows for c in row] + list(node.items)
    )
    return [node, *(n for c in children for n in walk(c))]


def test_result_tables() -> None:
    result: dict[str, Any] = {
        "d_min": 18.0,
        "ratio": 0.333333333333,
        "ok": True,
        "nothing": None,
        "links": [23.0, 22.0, 15.0],
        "samples": [float(i) for i in range(500)],
        "task_points": [{"label": "A", "x": 1.5, "y": 2.0}, {"label": "B", "x": 3.0}],
        "bands": [[16.0, 30.0], [31.0, 32.0]],
        "boundary": [[float(i), float(-i)] for i in range(100)],
        "cases": [{"name": "ideal", "points": [{"x": 1.0}]}],
        "nested": {"grid": {"step": [0.5, 0.5]}},
        "notes": ["left out"],
    }
    view = result_view(result, leave_out=("notes",))
    entries = dict(view.entries)
    assert "notes" not in entries
    assert (entries["d_min"].text, entries["ratio"].text, entries["ratio"].title) == (
        "18",
        "0.333333",
        "0.333333333333",
    )
    assert (entries["ok"].text, entries["nothing"].text) == ("true", "—")
    assert (entries["links"].kind, entries["links"].text) == ("inline", "[23, 22, 15]")
    assert entries["samples"].kind == "summary"
    assert entries["samples"].text.startswith("500 values; min 0, max 499, mean 249.5")
    records = entries["task_points"]
    assert records.kind == "records" and records.columns == ("label", "x", "y")
    assert [c.text for c in records.rows[1]] == ["B", "3", ""]
    assert entries["bands"].kind == "matrix" and len(entries["bands"].rows) == 2
    assert entries["boundary"].kind == "summary" and "[0, 99], [-99, 0]" in entries["boundary"].text
    assert entries["cases"].kind == "list" and entries["cases"].items[0].kind == "object"
    assert dict(dict(entries["nested"].entries)["grid"].entries)["step"].text == "[0.5, 0.5]"
    assert format_scalar(float("nan")) == "nan" and format_scalar(12345678.0) == "12345678"


def test_deep_results_become_json_text() -> None:
    deep: Any = 1
    for _ in range(10):
        deep = {"x": deep}
    assert any(n.kind == "json" for n in walk(result_view({"deep": deep})))


def test_compact_json_keeps_short_values_on_one_line() -> None:
    text = compact_json(
        {
            "lengths": [30.0, 17.0, 18.0, 25.0],
            "ground": 0,
            "chains": [
                {"name": "a" * 30, "lengths": [1.0, 2.0, 3.0]},
                {"name": "b" * 30, "lengths": [4.0]},
            ],
        }
    )
    assert json.loads(text)["chains"][1]["lengths"] == [4.0]
    assert '  "lengths": [30.0, 17.0, 18.0, 25.0],\n' in text
    assert compact_json({"a": 1}) == '{"a": 1}'


FIXTURE_PAGE = """\
# Four-bar chains

A chain is *rigid* when $\\sum_i l_i = 0$; here <b>raw HTML</b> stays text.

## Method

$$
Q = \\sum_{i=1}^{n} \\varepsilon_i^2
$$

| link | length |
|------|--------|
| 1    | 15     |

See [the serial arms](planar-serial.md#errata), [the index](README.md) and
[a paper](https://doi.org/10.1000/x). A bad formula: $\\frac{1}{$.

## Citation

A. Author, "Chains", *Journal* 1 (2000) 1–2.

## After
Not part of the citation.
"""


def test_method_page_renders_mathml_summary_and_citation(tmp_path: Path) -> None:
    (tmp_path / "methods").mkdir()
    (tmp_path / "methods" / "chains.md").write_text(FIXTURE_PAGE)
    (tmp_path / "methods" / "Not A Slug.md").write_text("# no")
    docs = MethodDocs(tmp_path)
    assert docs.slugs() == ["chains"]
    page = docs.page("chains")
    assert page is not None and page.title == "Four-bar chains"
    assert '<math display="block">' in page.html and "<mfrac>" not in page.summary_html
    assert "<math" in page.summary_html and "Method" not in page.summary_html
    assert "http://www.w3.org/1998/Math/MathML" not in page.html
    assert "&lt;b&gt;raw HTML&lt;/b&gt;" in page.html
    assert '<div class="table-wrap"><table>' in page.html
    assert 'href="/methods/planar-serial#errata"' in page.html
    assert 'href="/methods"' in page.html and 'href="https://doi.org/10.1000/x"' in page.html
    assert '<code class="tex">' in page.html  # the bad formula, shown as its source
    assert "Journal" in page.citation_html and "Not part" not in page.citation_html
    assert docs.page("nope") is None and docs.page("../etc/passwd") is None
    assert MethodDocs(tmp_path / "missing").slugs() == []


def test_the_shipped_method_pages_render() -> None:
    docs = MethodDocs(default_docs_dir())
    needed = {d.method_doc for d in default_registry() if d.method_doc}
    assert needed <= set(docs.slugs())
    for slug in needed:
        page = docs.page(slug)
        assert page is not None, slug
        assert page.summary_html and page.citation_html, slug
        assert "<math" in page.html, slug
        assert '<code class="tex">' not in page.html, f"{slug}: a formula did not convert"


def test_method_paths_in_descriptions_become_links_and_the_rest_is_escaped() -> None:
    from service.pages.renderer import link_method_pages

    html = str(link_method_pages("See docs/methods/planar-serial.md, <b>not</b> docs/x.md."))
    assert '<a href="/methods/planar-serial">the method page</a>' in html
    assert "&lt;b&gt;not&lt;/b&gt; docs/x.md" in html
