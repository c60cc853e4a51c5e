"""A job in Jupyter: everything from the service is escaped; plots are inline PNGs."""

from __future__ import annotations

import base64
import re

from dexlab.documents import Artifact, JobStatus
from dexlab.notebook import job_html, notebook_shell, progress_html

HOSTILE = '<script>alert("x")</script> & <img src=x onerror=alert(1)>'


def status(state: str, **extra: object) -> JobStatus:
    return JobStatus.from_document(
        {"jobID": "j<1>", "processID": "p&q", "status": state, "progress": 40,
         "message": HOSTILE, **extra}
    )  # fmt: skip


def assert_inert(html: str) -> None:
    assert "<script" not in html and "<img src=x" not in html
    assert "onerror=alert(1)>" not in html


def test_status_message_and_ids_are_escaped() -> None:
    html = job_html(status("running"))
    assert_inert(html)
    assert "&lt;script&gt;" in html and "j&lt;1&gt;" in html and "p&amp;q" in html
    assert '<progress max="100" value="40"' in html


def test_failure_notes_plots_and_files_are_escaped() -> None:
    failed = status("failed", error={"type": "job-error", "title": HOSTILE, "detail": HOSTILE})
    png = b"\x89PNG\r\n\x1a\n" + b"<script>"  # bytes are base64, never text
    plot = Artifact(name='a"b.png', media_type="image/png", title=HOSTILE)
    html = job_html(failed, notes=[HOSTILE, "plain"], plots=[(plot, png)], files=[plot])
    assert_inert(html)
    assert html.count("&lt;script&gt;") >= 4
    assert "<progress" not in html  # it has ended
    data = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', html)
    assert data is not None and base64.b64decode(data.group(1)) == png
    assert 'alt="&lt;script&gt;' in html and "a&quot;b.png" in html


def test_a_plot_that_could_not_be_fetched_says_why_escaped() -> None:
    plot = Artifact(name="map.png", media_type="image/png", title="Map")
    html = job_html(status("successful"), plots=[(plot, HOSTILE)])
    assert_inert(html)
    assert "dexlab-plot-error" in html and "<img" not in html


def test_progress_line_is_escaped() -> None:
    html = progress_html("<b>label</b>", status("running"))
    assert_inert(html)
    assert "&lt;b&gt;label" in html and 'value="40"' in html


def test_outside_a_kernel_there_is_no_notebook() -> None:
    assert notebook_shell() is None
