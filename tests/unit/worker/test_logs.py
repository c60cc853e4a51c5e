"""Log lines (worker.logs): the JSON and text formats, the bound IDs, uvicorn's and
Celery's records, and the configuration the entry points apply."""

from __future__ import annotations

import asyncio
import json
import logging
import os
import subprocess
import sys
import threading
from typing import Any

import pytest

from worker.logs import (
    JsonLineFormatter,
    LogContextFilter,
    LogSettings,
    TextLineFormatter,
    log_context,
    logging_config,
)


def record(name: str = "dexlab.test", msg: str = "hello %s", args: Any = ("world",),
           **extra: Any) -> logging.LogRecord:  # fmt: skip
    made = logging.LogRecord(name, logging.INFO, __file__, 1, msg, args, None)
    made.__dict__.update(extra)
    return made


def as_json(made: logging.LogRecord) -> dict[str, Any]:
    LogContextFilter().filter(made)
    line = JsonLineFormatter().format(made)
    assert "\n" not in line
    parsed: dict[str, Any] = json.loads(line)
    return parsed


def test_a_json_line_has_the_fields_and_only_the_ids_bound() -> None:
    line = as_json(record())
    assert line["message"] == "hello world"
    assert line["level"] == "INFO" and line["logger"] == "dexlab.test"
    assert line["time"].endswith("Z") and "T" in line["time"]
    assert isinstance(line["process"], int)
    assert "request_id" not in line and "job_id" not in line


def test_bound_ids_reach_records_made_inside_the_block_and_no_further() -> None:
    with log_context(request_id="r-1"), log_context(job_id="j-1"):
        inner = as_json(record())
    outer = as_json(record())
    assert (inner["request_id"], inner["job_id"]) == ("r-1", "j-1")
    assert "request_id" not in outer and "job_id" not in outer


def test_an_explicit_extra_wins_over_the_bound_id() -> None:
    with log_context(job_id="bound"):
        assert as_json(record(job_id="explicit"))["job_id"] == "explicit"


def test_threads_do_not_inherit_ids_but_tasks_do() -> None:
    seen: dict[str, Any] = {}

    def in_thread() -> None:
        seen["thread"] = as_json(record()).get("request_id")

    async def in_task() -> None:
        seen["task"] = as_json(record()).get("request_id")

    async def main() -> None:
        with log_context(request_id="r-2"):
            await asyncio.create_task(in_task())
            worker = threading.Thread(target=in_thread)
            worker.start()
            worker.join()

    asyncio.run(main())
    assert seen == {"task": "r-2", "thread": None}


def test_log_context_refuses_unknown_fields() -> None:
    with pytest.raises(TypeError, match="takes"), log_context(user="x"):
        pass


def test_uvicorn_access_lines_carry_the_request_fields() -> None:
    access = record("uvicorn.access", '%s - "%s %s HTTP/%s" %d',
                    ("127.0.0.1:5000", "GET", "/v1/jobs?limit=2", "1.1", 200))  # fmt: skip
    line = as_json(access)
    assert line["message"] == '127.0.0.1:5000 - "GET /v1/jobs?limit=2 HTTP/1.1" 200'
    assert (line["method"], line["path"], line["status"]) == ("GET", "/v1/jobs?limit=2", 200)


def test_celery_task_lines_name_their_job() -> None:
    task = record("celery.app.trace", "Task %(name)s[%(id)s] succeeded", None,
                  data={"id": "job-7", "name": "dexlab.run_job"})  # fmt: skip
    assert as_json(task)["job_id"] == "job-7"


def test_a_bad_format_and_a_traceback_still_make_one_json_line() -> None:
    try:
        raise ValueError("broken\nacross lines")
    except ValueError:
        failed = record(msg="%d apples", args=("not a number",), exc_info=sys.exc_info())
    line = as_json(failed)
    assert "%d apples" in line["message"]
    assert "ValueError: broken" in line["exception"]


def test_the_text_format_shows_the_same_fields() -> None:
    with log_context(request_id="r-3", job_id="j-3"):
        made = record()
        LogContextFilter().filter(made)
    text = TextLineFormatter().format(made)
    assert text.endswith("dexlab.test INFO hello world request_id=r-3 job_id=j-3")


def test_the_configuration_hands_uvicorns_records_to_the_one_handler() -> None:
    config = logging_config("json", "warning")
    assert config["root"]["level"] == "WARNING"
    assert config["formatters"]["dexlab"]["()"] is JsonLineFormatter
    for name in ("uvicorn", "uvicorn.error", "uvicorn.access"):
        assert config["loggers"][name] == {"handlers": [], "propagate": True}
    assert logging_config("text", logging.DEBUG)["formatters"]["dexlab"]["()"] is (
        TextLineFormatter
    )


def test_the_format_is_given_never_read(monkeypatch: pytest.MonkeyPatch) -> None:
    """The logs section reads no environment (the settings tree does, once, in the
    entry point: tests/unit/test_settings.py)."""
    monkeypatch.setenv("DEXLAB_LOG_FORMAT", "json")
    assert LogSettings().log_format == "text"
    assert LogSettings(log_format="json").log_format == "json"
    with pytest.raises(ValueError, match="log_format"):
        LogSettings(log_format="xml")  # type: ignore[arg-type]


@pytest.mark.parametrize("log_format", ["json", "text"])
def test_a_process_knows_the_format_it_writes(log_format: str) -> None:
    """What a pool's supervisor hands its spawned processes (they log as it does)."""
    script = (
        "from worker.logs import configure_logging, current_log_format\n"
        "print(current_log_format())\n"
        f"configure_logging({log_format!r})\n"
        "print(current_log_format())\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=60, check=True,
                          env={**os.environ, "DEXLAB_LOG_FORMAT": "json"})  # fmt: skip
    assert done.stdout.split() == ["text", log_format]


def test_printed_output_becomes_json_lines_in_a_process_that_asks() -> None:
    script = (
        "import os, sys, time\n"
        "from worker.logs import configure_logging, stdout_as_log_lines\n"
        "configure_logging('json')\n"
        "stdout_as_log_lines('celery.stdout')\n"
        "print('\\nworker: Warm shutdown (MainProcess)', flush=True)\n"
        "os.write(1, b'straight to the descriptor\\n')\n"
        "time.sleep(0.5)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=60, check=True)  # fmt: skip
    assert done.stdout == ""
    lines = [json.loads(text) for text in done.stderr.splitlines()]
    assert [line["message"] for line in lines] == [
        "worker: Warm shutdown (MainProcess)",
        "straight to the descriptor",
    ]
    assert {line["logger"] for line in lines} == {"celery.stdout"}
