"""The study explorer's table (worker.studies.design_table): paging, sorting and
filtering against a plain Python reference, stable cursors, scatter points and bins,
and the table read from a real study's designs.npz."""

from __future__ import annotations

import io
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY
from worker.studies.design_table import (
    SCATTER_BINS,
    SCATTER_POINTS,
    DesignColumn,
    DesignQuery,
    DesignQueryError,
    DesignTable,
    DesignTables,
    design_page,
    design_scatter,
)
from worker.studies.spec import StudySpec

CODES = ("", "refused", "no-value", "failed")


def synthetic(n: int, seed: int = 0) -> DesignTable:
    """n designs: two parameters, two objectives (NaN where infeasible), some ties."""
    rng = np.random.default_rng(seed)
    params = rng.integers(0, 5, size=(n, 2)).astype(float)
    objectives = np.round(rng.random((n, 2)), 2)
    feasible = rng.random(n) > 0.2
    objectives[~feasible] = np.nan
    codes = np.where(feasible, 0, rng.integers(1, 4, size=n))
    columns = (DesignColumn("a", "a", "parameter", "m"), DesignColumn("b", "b", "parameter", "-"),
               DesignColumn("f", "f|min", "objective", "-", "f", "max"),
               DesignColumn("g", "g", "objective", "m", "g", "min"))  # fmt: skip
    pareto = feasible & (rng.random(n) > 0.9)
    return DesignTable(columns, np.arange(n, dtype=np.int64), np.hstack([params, objectives]),
                       feasible, pareto, codes.astype(np.int64), CODES,
                       np.zeros(n, dtype=np.int64), ("",))  # fmt: skip


def reference(table: DesignTable, query: DesignQuery) -> list[int]:
    """The designs a query keeps, in order, by plain Python."""
    rows = []
    for r in range(table.count):
        v = dict(zip([c.key for c in table.columns], table.values[r], strict=True))
        if query.feasible is not None and bool(table.feasible[r]) != query.feasible:
            continue
        if query.pareto is not None and bool(table.pareto[r]) != query.pareto:
            continue
        if query.reason is not None and CODES[table.reason_code[r]] != query.reason:
            continue
        if any((lo is not None and not v[k] >= lo) or (hi is not None and not v[k] <= hi)
               for k, lo, hi in query.ranges):  # fmt: skip
            continue
        rows.append(r)

    def key(r: int) -> tuple[Any, ...]:
        if query.sort is None:
            return (not table.feasible[r], r)
        name = query.sort.lstrip("-")
        keys = [c.key for c in table.columns]
        value = float(r) if name == "index" else table.values[r, keys.index(name)]
        missing = bool(np.isnan(value))
        signed = 0.0 if missing else (-value if query.sort.startswith("-") else value)
        return (not table.feasible[r], missing, signed, r)

    return sorted(rows, key=key)


def every_page(table: DesignTable, query: DesignQuery, limit: int) -> list[int]:
    seen, cursor = [], None
    while True:
        page = design_page(table, query, limit, cursor)
        seen += [d["index"] for d in page["designs"]]
        cursor = page["next_cursor"]
        if cursor is None:
            return seen


queries = st.builds(
    DesignQuery,
    sort=st.sampled_from([None, "a", "-a", "f", "-f", "g", "-g", "index", "-index"]),
    feasible=st.sampled_from([None, True, False]),
    pareto=st.sampled_from([None, True, False]),
    ranges=st.sampled_from([(), (("f", 0.2, 0.8),), (("a", None, 2.0), ("g", 0.5, None))]),
    reason=st.sampled_from([None, "refused", "failed"]),
)


@settings(max_examples=60, deadline=None)
@given(query=queries, limit=st.integers(1, 40), seed=st.integers(0, 5))
def test_pages_are_the_reference_order_cut_into_pieces(
    query: DesignQuery, limit: int, seed: int
) -> None:
    table = synthetic(97, seed)
    expected = reference(table, query)
    assert every_page(table, query, limit) == expected
    assert design_page(table, query, limit, None)["matched"] == len(expected)


def test_a_page_names_each_value_by_its_column_and_says_why_a_design_fails() -> None:
    table = synthetic(50)
    page = design_page(table, DesignQuery(feasible=False), 5, None)
    row = page["designs"][0]
    assert set(row["values"]) == {"a", "b", "f", "g"} and row["values"]["f"] is None
    assert row["reason_code"] in CODES[1:] and row["feasible"] is False
    assert page["total"] == 50 and page["next_cursor"] is not None


def test_a_cursor_of_another_query_or_not_ours_is_refused() -> None:
    table = synthetic(30)
    cursor = design_page(table, DesignQuery(sort="a"), 5, None)["next_cursor"]
    with pytest.raises(DesignQueryError) as other:
        design_page(table, DesignQuery(sort="-a"), 5, cursor)
    assert other.value.parameter == "cursor"
    with pytest.raises(DesignQueryError, match="not a cursor"):
        design_page(table, DesignQuery(), 5, "%%%")
    for query, parameter in ((DesignQuery(sort="nope"), "sort"),
                             (DesignQuery(ranges=(("nope", 1, 2),)), "range"),
                             (DesignQuery(reason="bored"), "reason")):  # fmt: skip
        with pytest.raises(DesignQueryError) as bad:
            design_page(table, query, 5, None)
        assert bad.value.parameter == parameter


def test_ten_thousand_designs_page_quickly_and_scatter_as_points() -> None:
    table = synthetic(SCATTER_POINTS)
    assert every_page(table, DesignQuery(sort="-f"), 1000) == reference(
        table, DesignQuery(sort="-f")
    )
    scatter = design_scatter(table, "f", "g", DesignQuery())
    assert scatter["bins"] is None
    assert scatter["matched"] == int(table.feasible.sum()) == len(scatter["points"]["x"])


def test_beyond_ten_thousand_the_scatter_is_bins_and_the_front() -> None:
    table = synthetic(3 * SCATTER_POINTS)
    scatter = design_scatter(table, "f", "g", DesignQuery())
    counts = np.array(scatter["bins"]["counts"])
    assert counts.shape == (SCATTER_BINS, SCATTER_BINS)
    assert counts.sum() == scatter["matched"] == int(table.feasible.sum())
    assert scatter["points"]["pareto"] and all(scatter["points"]["pareto"])
    assert len(scatter["points"]["index"]) == int(table.pareto.sum())


def test_the_table_of_a_real_study_and_its_cache() -> None:
    spec = StudySpec.model_validate({
        "process": "planar3r-dexterity-map",
        "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
        "vary": {"links[0]": [5, 20, 4], "links[2]": [2, 10, 3]},
        "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"}, "plots": False,
    })  # fmt: skip
    outcome = STUDY.run(spec, RecordingContext())
    data = next(a.data for a in outcome.artifacts if a.name == "designs.npz")
    reads: list[int] = []
    tables = DesignTables(capacity=1)

    def read() -> bytes:
        reads.append(1)
        return data

    table = tables.get("e1", read)
    assert tables.get("e1", read) is table and len(reads) == 1
    tables.get("e2", read)
    tables.get("e1", read)
    assert len(reads) == 3  # capacity one: e1 was dropped for e2
    assert [c.key for c in table.columns] == ["links_0", "links_2", "task_points_d_z_min",
                                              "links_sum"]  # fmt: skip
    assert [c.kind for c in table.columns] == ["parameter"] * 2 + ["objective"] * 2
    with np.load(io.BytesIO(data)) as z:
        assert table.pareto.sum() == len(z["pareto"])
    best = design_page(table, DesignQuery(sort="links_sum"), 1, None)["designs"][0]
    assert best["values"]["links_sum"] == pytest.approx(5 + 14 + 2)  # the shortest arm
