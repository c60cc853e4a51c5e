"""A design study's page as an explorer, without JavaScript (over ASGI, the real app):
the designs table sorts, filters and pages by links, infeasible designs are grouped by
reason, a design opens as a job of its own or in the process form, and a chunk's page
leads to its study."""

from __future__ import annotations

import html
import re
from pathlib import Path

import pytest

from tests.unit.service.test_designs_api import STUDY
from tests.unit.service.test_reuse_api import ALICE, BOB, key, service

pytestmark = pytest.mark.anyio

PAGE = {"Accept": "text/html"}


def rows(page: str) -> list[int]:
    return [int(i) for i in re.findall(r'<tr id="design-(\d+)"', page)]


async def test_the_study_page_explores_its_designs_without_javascript(tmp_path: Path) -> None:
    async with service(tmp_path, "owner") as s:
        headers = {**key(ALICE), **PAGE}
        url = "/v1/processes/design-study/execution"
        job = (await s.client.post(url, json={"inputs": {**STUDY, "chunk_size": 10}},
                                   headers=key(ALICE))).json()  # fmt: skip
        assert s.drain(limit=1) == 1  # the split: the page lists the chunks
        running = (await s.client.get(f"/v1/jobs/{job['jobID']}", headers=headers)).text
        assert 'id="chunks-title"' in running and running.count('<a href="/v1/jobs/') >= 3
        chunk = re.search(r'<a href="/v1/jobs/([0-9a-f-]+)"><code>', running)
        assert chunk is not None
        chunk_page = (await s.client.get(f"/v1/jobs/{chunk.group(1)}", headers=headers)).text
        assert f'<a href="/v1/jobs/{job["jobID"]}">' in chunk_page  # its title leads to the study
        assert 'href="/v1/processes/design-study-chunk"' not in chunk_page
        s.drain()
        page = (await s.client.get(f"/v1/jobs/{job['jobID']}", headers=headers)).text
        assert 'id="designs"' in page and len(rows(page)) == 25
        assert "Infeasible designs by reason" in page and "inputs.links[0]" in page
        first = rows(page)
        assert first[:20] == sorted(first[:20])  # feasible first, by index
        sort = html.unescape(re.search(r'href="([^"]+)" data-sort="links_sum"', page).group(1))
        by_sum = (await s.client.get(sort, headers=headers)).text
        assert 'aria-sort="ascending"' in by_sum and rows(by_sum) != first
        nxt = html.unescape(re.search(r'href="([^"]+)" id="designs-next"', page).group(1))
        second = (await s.client.get(nxt, headers=headers)).text
        assert len(rows(second)) == 5 and not set(rows(second)) & set(first)
        refused = (await s.client.get(f"/v1/jobs/{job['jobID']}?feasible=false",
                                      headers=headers)).text  # fmt: skip
        assert len(rows(refused)) == 10 and "refused (inputs.links[0])" in refused
        odd = (await s.client.get(f"/v1/jobs/{job['jobID']}?sort=nope", headers=headers)).text
        assert "no column 'nope'" in html.unescape(odd) and len(rows(odd)) == 25
        design = first[0]
        form = {**key(ALICE), "Origin": "http://dexlab.test"}
        opened = await s.client.post(f"/pages/jobs/{job['jobID']}/designs/{design}/run",
                                     headers=form)  # fmt: skip
        assert opened.status_code == 303
        single = (await s.client.get(opened.headers["location"], headers=key(ALICE))).json()
        assert single["processID"] == "planar3r-dexterity-map"
        edit = await s.client.get(f"/pages/jobs/{job['jobID']}/designs/{design}/edit",
                                  headers=headers)  # fmt: skip
        assert edit.status_code == 200 and f"Design {design} of study" in edit.text
        assert "&#34;plots&#34;: true" in edit.text or '"plots": true' in html.unescape(edit.text)
        past = await s.client.get(f"/pages/jobs/{job['jobID']}/designs/30/edit", headers=headers)
        assert past.status_code == 404
        theirs = await s.client.get(f"/pages/jobs/{job['jobID']}/designs/0/edit",
                                    headers={**key(BOB), **PAGE})  # fmt: skip
        assert theirs.status_code == 404
