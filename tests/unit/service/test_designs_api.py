"""``GET /v1/jobs/{jobID}/designs`` and ``.../designs/scatter`` over the real app
(ASGI, embedded store, the queue drained in-process): paging with the ``next`` link,
sorting, filters, the columns' units and descriptions, owner scoping, and 422 problems
naming the parameter."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.unit.service.test_reuse_api import ALICE, BOB, key, service

pytestmark = pytest.mark.anyio

STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
    "vary": {"links[0]": [-5, 20, 6], "links[2]": [2, 10, 5]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    "plots": False,
}  # fmt: skip


async def test_a_study_is_paged_sorted_and_filtered(tmp_path: Path) -> None:
    async with service(tmp_path, "owner") as s:
        url = "/v1/processes/design-study/execution"
        job = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        s.drain()
        designs = f"/v1/jobs/{job['jobID']}/designs"
        first = (await s.client.get(designs, params={"limit": 7}, headers=key(ALICE))).json()
        assert first["total"] == 30 and first["matched"] == 30 and len(first["designs"]) == 7
        columns = {c["key"]: c for c in first["columns"]}
        assert columns["links_sum"]["goal"] == "min" and columns["links_0"]["kind"] == "parameter"
        assert columns["links_0"]["label"] == "links[0] [units]"
        assert columns["task_points_d_z_min"]["label"] == "min(d_z)"
        assert columns["links_sum"]["label"] == "sum(l_i) [units]"
        assert (
            columns["task_points_d_z_min"]["symbol"]
            and columns["task_points_d_z_min"]["description"]
        )
        seen = [d["index"] for d in first["designs"]]
        following = first
        while nxt := next((ln["href"] for ln in following["links"] if ln["rel"] == "next"), None):
            following = (await s.client.get(nxt, headers=key(ALICE))).json()
            seen += [d["index"] for d in following["designs"]]
        assert sorted(seen) == list(range(30))
        feasible = [d["feasible"] for d in first["designs"]]
        assert feasible == sorted(feasible, reverse=True)  # feasible first
        refused = (await s.client.get(designs, params={"feasible": "false"},
                                      headers=key(ALICE))).json()  # fmt: skip
        assert refused["matched"] == 10  # links[0] of -5 and 0 are refused
        assert {d["reason_code"] for d in refused["designs"]} == {"refused"}
        assert {d["reason_field"] for d in refused["designs"]} == {"inputs.links[0]"}
        short = (await s.client.get(designs, params={"sort": "links_sum", "range": "links_2:4:",
                                                     "feasible": "true"},
                                    headers=key(ALICE))).json()  # fmt: skip
        sums = [d["values"]["links_sum"] for d in short["designs"]]
        assert sums == sorted(sums) and all(d["values"]["links_2"] >= 4 for d in short["designs"])
        axes = {"x": "links_sum", "y": "task_points_d_z_min"}
        scatter = (await s.client.get(f"{designs}/scatter", params=axes, headers=key(ALICE))).json()
        assert scatter["matched"] == 20 and scatter["bins"] is None
        assert len(scatter["points"]["x"]) == 20 and any(scatter["points"]["pareto"])
        hidden = await s.client.get(designs, headers=key(BOB))
        assert hidden.status_code == 404


async def test_bad_queries_and_jobs_without_designs_are_problems(tmp_path: Path) -> None:
    async with service(tmp_path, "owner") as s:
        url = "/v1/processes/design-study/execution"
        job = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        designs = f"/v1/jobs/{job['jobID']}/designs"
        waiting = await s.client.get(designs, headers=key(ALICE))
        assert waiting.json()["type"].endswith("/result-not-ready")
        s.drain()
        for params, field in (({"sort": "nope"}, "query.sort"), ({"range": "x"}, "query.range"),
                              ({"range": "links_0:a:"}, "query.range"),
                              ({"cursor": "zzz"}, "query.cursor"), ({"limit": 0}, "query.limit"),
                              ({"reason": "bored"}, "query.reason")):  # fmt: skip
            bad = await s.client.get(designs, params=params, headers=key(ALICE))
            assert bad.status_code == 422, (params, bad.text)
            assert bad.json()["errors"][0]["field"] == field, bad.json()
        missing_axis = await s.client.get(f"{designs}/scatter", params={"x": "links_0", "y": "q"},
                                          headers=key(ALICE))  # fmt: skip
        assert missing_axis.status_code == 422 and "query.y" in missing_axis.text
        other = (await s.submit(ALICE)).json()  # a four-bar job: no designs
        s.drain()
        none = await s.client.get(f"/v1/jobs/{other['jobID']}/designs", headers=key(ALICE))
        assert none.status_code == 404 and "not a design study" in none.json()["detail"]


async def test_infeasible_designs_are_grouped_by_reason(tmp_path: Path) -> None:
    async with service(tmp_path, "owner") as s:
        url = "/v1/processes/design-study/execution"
        job = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        s.drain()
        reasons = f"/v1/jobs/{job['jobID']}/designs/reasons"
        (group,) = (await s.client.get(reasons, headers=key(ALICE))).json()["groups"]
        assert (group["reason_code"], group["reason_field"], group["designs"]) == (
            "refused", "inputs.links[0]", 10)  # fmt: skip
        assert "…" in group["reason"] and "0.000001" in group["example"]
        assert (await s.client.get(reasons, headers=key(BOB))).status_code == 404
