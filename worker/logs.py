"""Log lines: one format for the API, the local pool and the Celery workers.

``DEXLAB_LOG_FORMAT=json`` (:class:`LogSettings`) writes each record as one JSON object
on one line (the default in the container image); ``text`` (the default elsewhere)
writes the same fields readably.  Every line has ``time`` (UTC, ISO 8601,
milliseconds), ``level``, ``logger``, ``message`` and ``process`` (the pid);
``request_id`` where a request is being served, ``job_id`` where a job is being run,
``exception`` with the traceback where there is one; uvicorn's access lines add
``client``, ``method``, ``path``, ``http_version`` and ``status``.

The IDs travel in a context variable (:func:`log_context`): the request-ID middleware
binds ``request_id`` around a request, the runner binds ``job_id`` around an attempt,
and a filter on the one handler copies them into each record.  Celery's own task lines
name their task, whose ID is the job ID.  :func:`configure_logging` is called by each
entry point (``dexlab serve``, ``dexlab worker``, with the settings' format; a spawned
pool process, with its supervisor's: :func:`current_log_format`); nothing here reads
the environment or runs at import.
"""

from __future__ import annotations

import contextlib
import json
import logging
import logging.config
import os
import sys
import threading
from collections.abc import Iterator, Mapping
from contextvars import ContextVar
from datetime import UTC, datetime
from types import MappingProxyType, TracebackType
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

__all__ = [
    "JsonLineFormatter",
    "LogContextFilter",
    "LogSettings",
    "TextLineFormatter",
    "configure_logging",
    "current_log_format",
    "log_context",
    "logging_config",
    "stdout_as_log_lines",
]

LogFormat = Literal["json", "text"]

#: The fields :func:`log_context` may bind, in the order lines show them.
CONTEXT_FIELDS = ("request_id", "job_id")

_EMPTY: Mapping[str, str] = MappingProxyType({})
#: The IDs bound where a record is made (a context variable: per thread and task).
_CONTEXT: ContextVar[Mapping[str, str]] = ContextVar("dexlab_log_context", default=_EMPTY)

#: uvicorn's access line: ``'%s - "%s %s HTTP/%s" %d'`` with these arguments.
_ACCESS_FIELDS = ("client", "method", "path", "http_version", "status")


class LogSettings(BaseModel):
    """The logs section of the settings: how the processes log (``DEXLAB_LOG_FORMAT``)."""

    model_config = ConfigDict(extra="ignore", frozen=True)

    log_format: LogFormat = Field(
        "text",
        description="json: one JSON object a line (the container default); text: readable lines.",
    )


@contextlib.contextmanager
def log_context(**fields: str | None) -> Iterator[None]:
    """Bind ``request_id`` and/or ``job_id`` to every record made inside the block
    (in this thread or task, and the tasks it starts)."""
    unknown = set(fields) - set(CONTEXT_FIELDS)
    if unknown:
        raise TypeError(f"log_context() takes {CONTEXT_FIELDS}, not {sorted(unknown)}")
    bound = {**_CONTEXT.get(), **{k: v for k, v in fields.items() if v is not None}}
    token = _CONTEXT.set(MappingProxyType(bound))
    try:
        yield
    finally:
        _CONTEXT.reset(token)


class LogContextFilter(logging.Filter):
    """Copies the bound IDs into each record (a record's own ``extra`` wins); a Celery
    task line gets its task's ID, which is the job ID."""

    def filter(self, record: logging.LogRecord) -> bool:
        for name, value in _CONTEXT.get().items():
            if not hasattr(record, name):
                setattr(record, name, value)
        if not hasattr(record, "job_id") and record.name.startswith("celery"):
            data = getattr(record, "data", None)
            if isinstance(data, Mapping) and isinstance(data.get("id"), str):
                record.job_id = data["id"]
        return True


def _message(record: logging.LogRecord) -> str:
    """The record's message; a bad format/argument pair is shown, never raised."""
    try:
        return record.getMessage()
    except Exception:
        return f"{record.msg!s} {record.args!r}"


def _access_fields(record: logging.LogRecord) -> dict[str, Any]:
    if record.name != "uvicorn.access" or not isinstance(record.args, tuple):
        return {}
    if len(record.args) != len(_ACCESS_FIELDS):
        return {}
    return dict(zip(_ACCESS_FIELDS, record.args, strict=True))


def _time(record: logging.LogRecord) -> str:
    moment = datetime.fromtimestamp(record.created, tz=UTC)
    return moment.isoformat(timespec="milliseconds").replace("+00:00", "Z")


class JsonLineFormatter(logging.Formatter):
    """One JSON object a line (non-ASCII escaped, so a line is always one line)."""

    def format(self, record: logging.LogRecord) -> str:
        line: dict[str, Any] = {
            "time": _time(record),
            "level": record.levelname,
            "logger": record.name,
            "message": _message(record),
            "process": record.process,
        }
        for name in CONTEXT_FIELDS:
            value = getattr(record, name, None)
            if value is not None:
                line[name] = str(value)
        line.update(_access_fields(record))
        if record.exc_info:
            line["exception"] = self.formatException(record.exc_info)
        elif record.exc_text:
            line["exception"] = record.exc_text
        if record.stack_info:
            line["stack"] = self.formatStack(record.stack_info)
        return json.dumps(line, default=str)


class TextLineFormatter(logging.Formatter):
    """``time pid logger LEVEL message request_id=... job_id=...`` (then a traceback)."""

    def format(self, record: logging.LogRecord) -> str:
        parts = [_time(record), str(record.process), record.name, record.levelname,
                 _message(record)]  # fmt: skip
        parts += [
            f"{name}={getattr(record, name)}"
            for name in CONTEXT_FIELDS
            if getattr(record, name, None) is not None
        ]
        text = " ".join(parts)
        if record.exc_info:
            text += "\n" + self.formatException(record.exc_info)
        if record.stack_info:
            text += "\n" + self.formatStack(record.stack_info)
        return text


def logging_config(log_format: LogFormat, level: str | int = "INFO") -> dict[str, Any]:
    """A :func:`logging.config.dictConfig` document: one stderr handler on the root in
    ``log_format``, uvicorn's loggers handing their records to it (so the access and
    error logs share the format).  Also uvicorn's ``log_config``."""
    formatter = JsonLineFormatter if log_format == "json" else TextLineFormatter
    level_name = logging.getLevelName(level) if isinstance(level, int) else level.upper()
    return {
        "version": 1,
        "disable_existing_loggers": False,
        "filters": {"context": {"()": LogContextFilter}},
        "formatters": {"dexlab": {"()": formatter}},
        "handlers": {
            "stderr": {
                "class": "logging.StreamHandler",
                "stream": "ext://sys.stderr",
                "formatter": "dexlab",
                "filters": ["context"],
            }
        },
        "root": {"level": level_name, "handlers": ["stderr"]},
        "loggers": {
            **{
                name: {"handlers": [], "propagate": True}
                for name in ("uvicorn", "uvicorn.error", "uvicorn.access")
            },
            # multiprocessing's and billiard's logger does not propagate (a Celery
            # pool process's death is logged there): give it the handler.
            "multiprocessing": {"handlers": ["stderr"], "propagate": False, "level": "WARNING"},
        },
    }


def _log_uncaught(
    kind: type[BaseException], error: BaseException, trace: TracebackType | None
) -> None:
    logging.getLogger("dexlab").critical("uncaught exception", exc_info=(kind, error, trace))


def _log_uncaught_in_thread(args: threading.ExceptHookArgs) -> None:
    if args.exc_type is SystemExit or args.exc_value is None:
        return
    logging.getLogger("dexlab").critical(
        "uncaught exception in thread %s",
        args.thread.name if args.thread is not None else "?",
        exc_info=(args.exc_type, args.exc_value, args.exc_traceback),
    )


def configure_logging(log_format: LogFormat, level: str | int = "INFO") -> dict[str, Any]:
    """Configure this process's logging (an entry point calls it once, with the
    settings' ``log_format``).  Warnings and uncaught exceptions are logged in the same
    format.  Returns the configuration (for uvicorn's ``log_config``)."""
    config = logging_config(log_format, level)
    logging.config.dictConfig(config)
    logging.captureWarnings(True)
    sys.excepthook = _log_uncaught
    threading.excepthook = _log_uncaught_in_thread
    return config


def current_log_format() -> LogFormat:
    """The format this process's root logger writes in (``text`` when it has no
    :func:`configure_logging` handler): what a spawned pool process is told to use,
    so that it logs as its supervisor does."""
    for handler in logging.getLogger().handlers:
        if isinstance(handler.formatter, JsonLineFormatter):
            return "json"
    return "text"


def stdout_as_log_lines(logger_name: str = "dexlab.stdout") -> None:
    """Make whatever is printed to this process's standard output (file descriptor 1,
    which forked children share) into log lines of ``logger_name``, one per non-blank
    line.  For a process whose libraries print (Celery prints its shutdown notices);
    the log handler itself writes to standard error."""
    read_end, write_end = os.pipe()
    sys.stdout.flush()
    os.dup2(write_end, 1)
    os.close(write_end)

    def forward() -> None:
        printed = logging.getLogger(logger_name)
        with os.fdopen(read_end, encoding="utf-8", errors="replace") as lines:
            for line in lines:
                if line.strip():
                    printed.info("%s", line.rstrip("\n"))

    threading.Thread(target=forward, name="stdout-to-log", daemon=True).start()
