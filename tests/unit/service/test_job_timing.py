"""Durations, time left and the words for them on the job pages."""

from __future__ import annotations

from datetime import UTC, datetime, timedelta

import pytest

from service.pages.job_timing import duration_s, duration_text, job_timing, remaining_s
from worker.contract import JobRecord, JobStatus

T0 = datetime(2026, 11, 28, 5, 0, tzinfo=UTC)


def job(status: JobStatus, progress: float = 0.0, **times: datetime | None) -> JobRecord:
    return JobRecord(job_id="j", process_id="p", status=status, inputs={}, created=T0,
                     updated=T0, progress=progress, **times)  # type: ignore[arg-type]  # fmt: skip


def test_a_running_job_counts_to_now_and_estimates_from_its_progress() -> None:
    running = job(JobStatus.RUNNING, 25.0, started=T0)
    now = T0 + timedelta(seconds=60)
    assert duration_s(running, now) == 60.0
    assert remaining_s(running, now) == pytest.approx(180.0)  # 60 s for 25 %: 180 s for 75 %
    timing = job_timing(running, now)
    assert timing == {"duration": "1 min 00 s", "running": True, "eta": "3 min 00 s",
                      "expires": ""}  # fmt: skip


def test_no_estimate_without_progress_and_none_once_finished() -> None:
    now = T0 + timedelta(seconds=5)
    assert remaining_s(job(JobStatus.RUNNING, 0.0, started=T0), now) is None
    done = job(JobStatus.SUCCESSFUL, 100.0, started=T0, finished=T0 + timedelta(seconds=2.5),
               expires=T0 + timedelta(days=7))  # fmt: skip
    assert duration_s(done, now + timedelta(hours=1)) == 2.5
    assert remaining_s(done, now) is None
    assert job_timing(done, now)["expires"] == "2026-12-05T05:00:00Z"


def test_a_queued_job_has_no_duration() -> None:
    assert duration_s(job(JobStatus.ACCEPTED, started=T0), T0) is None  # back in the queue
    assert job_timing(job(JobStatus.ACCEPTED), T0)["duration"] == ""


@pytest.mark.parametrize(
    ("seconds", "text"),
    [
        (None, ""),
        (0.42, "0.4 s"),
        (42.4, "42 s"),
        (185.5, "3 min 06 s"),
        (7800, "2 h 10 min"),
        (273600, "3 d 4 h"),
    ],
)
def test_duration_text(seconds: float | None, text: str) -> None:
    assert duration_text(seconds) == text
