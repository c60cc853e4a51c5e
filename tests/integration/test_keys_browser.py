"""The pages in headless Chromium on a service with API keys: log in, run an example,
follow it live, read the plot, log out; forms without their CSRF token are refused;
a revoked key's session ends.  Nothing leaves 127.0.0.1 (tests/browser.py)."""

from __future__ import annotations

import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest

from tests.browser import open_page, screenshot_dir
from tests.integration.servers import Deployment, deployment, dexlab_command

pytestmark = pytest.mark.integration

TIMEOUT_MS = 60_000
PROCESS = "planar2dof-conditioning-map"
ALICE = "alice-browser-secret-5e21b9"
BOB = "bob-browser-secret-0c7d41aa"


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    env = {"DEXLAB_API_KEYS": f"alice:{ALICE},bob:{BOB}"}
    with deployment("embedded", tmp_path_factory.mktemp("keys-pages"), env=env) as dep:
        yield dep


def log_in(page: Any, base_url: str, secret: str) -> None:
    page.goto(f"{base_url}/v1/processes/{PROCESS}")
    page.locator("header.site").get_by_role("link", name="Log in").click()
    page.wait_for_url(lambda url: urlsplit(url).path == "/login")
    page.get_by_label("API key").fill(secret)
    page.get_by_role("button", name="Log in").click()
    page.wait_for_url(f"**/v1/processes/{PROCESS}")


def test_log_in_run_an_example_follow_it_and_log_out(
    server: Deployment, browser: Any, tmp_path: Path
) -> None:
    shots = screenshot_dir(tmp_path)
    with open_page(browser) as offline:
        page = offline.page
        events: list[int] = []
        page.on(
            "response",
            lambda r: events.append(r.status) if urlsplit(r.url).path.endswith("/events") else None,
        )
        log_in(page, server.base_url, ALICE)
        assert "Signed in as alice" in page.locator("#signed-in-as").inner_text()
        (cookie,) = [c for c in page.context.cookies() if c["name"] == "dexlab_session"]
        assert cookie["httpOnly"] and cookie["sameSite"] == "Strict" and ALICE not in str(cookie)
        page.screenshot(path=str(shots / "signed-in-process-page.png"), full_page=True)
        page.locator("#example-0").get_by_role("button", name="Run this example").click()
        page.wait_for_url("**/v1/jobs/*", timeout=TIMEOUT_MS)
        job_url = page.url
        page.wait_for_selector("#job-progress[value='100']", timeout=TIMEOUT_MS)
        page.wait_for_selector("figure.plot img", timeout=TIMEOUT_MS)
        page.wait_for_load_state("networkidle")
        assert 200 in events, events  # live progress over the cookie
        widths = page.locator("figure.plot img").evaluate_all(
            "images => images.map(image => image.complete ? image.naturalWidth : 0)"
        )
        assert widths and all(w > 0 for w in widths), widths
        job_id = urlsplit(job_url).path.rsplit("/", 1)[-1]
        with_bob = server.client.get(
            f"/v1/jobs/{job_id}", headers={"Authorization": f"Bearer {BOB}"}
        )
        assert with_bob.status_code == 404  # the job is alice's
        page.screenshot(path=str(shots / "signed-in-job-page.png"), full_page=True)

        page.locator("header.site").get_by_role("button", name="Log out").click()
        page.wait_for_url(f"{server.base_url}/")
        assert page.locator("header.site").get_by_role("link", name="Log in").count() == 1
        assert not [c for c in page.context.cookies() if c["name"] == "dexlab_session"]
        assert not offline.external and not offline.console_errors, offline
        response = page.goto(job_url)  # (the browser logs this 401 as a console error)
        assert response is not None and response.status == 401
        assert page.get_by_role("link", name="Log in with your API key").count() == 1


def test_a_form_without_its_csrf_token_is_refused(server: Deployment, browser: Any) -> None:
    with open_page(browser) as offline:
        page = offline.page
        log_in(page, server.base_url, ALICE)
        token = page.locator("#example-0 input[name=csrf_token]").get_attribute("value")
        assert token
        inputs = page.locator("#example-0 textarea").input_value()
        action = f"{server.base_url}/pages/processes/{PROCESS}/run"
        origin = {"Origin": server.base_url}
        for form in ({"inputs": inputs}, {"inputs": inputs, "csrf_token": token[:-2] + "xx"}):
            refused = page.request.post(action, form=form, headers=origin, max_redirects=0)
            assert refused.status == 403, refused.text()
            assert "/problems/forbidden" in refused.text()
        accepted = page.request.post(
            action, form={"inputs": inputs, "csrf_token": token}, headers=origin, max_redirects=0
        )
        assert accepted.status == 303 and "/v1/jobs/" in accepted.headers["location"]
        # The cookie reads and posts forms; the JSON API's writes need the key itself.
        job_id = accepted.headers["location"].rsplit("/", 1)[-1]
        assert page.request.delete(f"{server.base_url}/v1/jobs/{job_id}").status == 401


def test_a_revoked_keys_session_ends(server: Deployment, browser: Any) -> None:
    with open_page(browser) as offline:
        page = offline.page
        log_in(page, server.base_url, BOB)
        assert page.goto(f"{server.base_url}/v1/jobs").status == 200
        revoked = subprocess.run(
            [*dexlab_command(), "keys", "revoke", "bob", "--data-dir", str(server.data_dir)],
            capture_output=True, text=True, timeout=60,
        )  # fmt: skip
        assert revoked.returncode == 0, revoked.stderr
        time.sleep(1.1)  # the key cache is at most a second old
        response = page.goto(f"{server.base_url}/v1/jobs")
        assert response is not None and response.status == 401
        assert "session has ended" in page.content()
