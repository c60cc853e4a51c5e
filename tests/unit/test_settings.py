"""The settings tree (service.config.Settings): each public environment variable maps to
its field, command-line options win over the environment, the sections read nothing,
and what is built from the tree (the app) reads no environment after it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel, SecretStr, ValidationError

from service.app import create_app
from service.config import ServiceSettings, Settings
from service.metrics.settings import MetricsSettings
from service.pages.settings import PageSettings
from worker.logs import LogSettings
from worker.settings import WorkerSettings

SECRET = "s3cret-s3cret-s3cret-s3cret-s3cret"

#: Every environment variable operators use today (they are public: none may go), with
#: a value other than the default and the field value it must give.
ENVIRONMENT: dict[str, tuple[str, Any]] = {
    "DEXLAB_LOG_FORMAT": ("json", "json"),
    "DEXLAB_METRICS": ("0", False),
    "DEXLAB_DOCS_DIR": ("/srv/dexlab-docs", Path("/srv/dexlab-docs")),
    "DEXLAB_EVENT_STREAM_SECONDS": ("60", 60.0),
    "DEXLAB_EVENT_POLL_SECONDS": ("1.5", 1.5),
    "DEXLAB_DATA_DIR": ("/var/lib/dexlab", Path("/var/lib/dexlab")),
    "DEXLAB_STORE_URL": ("postgresql://db/dexlab", "postgresql://db/dexlab"),
    "DEXLAB_WORKERS": ("7", 7),
    "DEXLAB_LEASE_SECONDS": ("20", 20.0),
    "DEXLAB_HEARTBEAT_SECONDS": ("0.5", 0.5),
    "DEXLAB_STORE_RETRY_SECONDS": ("9", 9.0),
    "DEXLAB_POLL_SECONDS": ("30", 30.0),
    "DEXLAB_MAX_ATTEMPTS": ("5", 5),
    "DEXLAB_MAX_TIME_LIMIT_S": ("60", 60.0),
    "DEXLAB_BROKER_URL": ("redis://broker:6379/0", "redis://broker:6379/0"),
    "DEXLAB_QUEUE": ("lab", "lab"),
    "DEXLAB_BROKER_VISIBILITY_TIMEOUT_S": ("3600", 3600.0),
    "DEXLAB_AMQP_CONSUMER_TIMEOUT_S": ("900", 900.0),
    "DEXLAB_SWEEP_SECONDS": ("0.5", 0.5),
    "DEXLAB_DELIVERY_BATCH_S": ("0", 0.0),
    "DEXLAB_REDISPATCH_AFTER_S": ("1", 1.0),
    "DEXLAB_MAX_QUEUED": ("5", 5),
    "DEXLAB_MAX_QUEUED_PER_KEY": ("3", 3),
    "DEXLAB_MAX_RUNNING_PER_KEY": ("2", 2),
    "DEXLAB_SUBMIT_RATE_PER_MIN": ("6", 6),
    "DEXLAB_RESULT_TTL_S": ("3600", 3600.0),
    "DEXLAB_WORKER_NICE": ("0", 0),
    "DEXLAB_REUSE": ("all", "all"),
    "DEXLAB_BUILD_ID": ("ci-42", "ci-42"),
    "DEXLAB_HOST": ("0.0.0.0", "0.0.0.0"),
    "DEXLAB_PORT": ("9000", 9000),
    "DEXLAB_LOG_LEVEL": ("debug", "debug"),
    "DEXLAB_MAX_BODY_BYTES": ("4096", 4096),
    "DEXLAB_MAX_JSON_DEPTH": ("16", 16),
    "DEXLAB_FORWARDED_ALLOW_IPS": ("10.0.0.0/8", "10.0.0.0/8"),
    "DEXLAB_OUTBOUND_ALLOW_HOSTS": ("hooks.example", "hooks.example"),
    "DEXLAB_OUTBOUND_TIMEOUT_S": ("2", 2.0),
    "DEXLAB_CALLBACK_MAX_ATTEMPTS": ("2", 2),
    "DEXLAB_API_KEYS": (f"alice:{SECRET}", SecretStr(f"alice:{SECRET}")),
    "DEXLAB_SESSION_SECRET": (SECRET, SecretStr(SECRET)),
    "DEXLAB_SESSION_SECONDS": ("600", 600.0),
    "DEXLAB_CORS_ORIGINS": ("https://a.example", "https://a.example"),
}

SECTIONS: tuple[type[BaseModel], ...] = (
    WorkerSettings,
    ServiceSettings,
    PageSettings,
    MetricsSettings,
    LogSettings,
)


@pytest.fixture
def clean_environment(monkeypatch: pytest.MonkeyPatch) -> pytest.MonkeyPatch:
    """No ``DEXLAB_*`` setting from the shell running the tests."""
    for name in ENVIRONMENT:
        monkeypatch.delenv(name, raising=False)
    return monkeypatch


def field_of(name: str) -> str:
    return name.removeprefix("DEXLAB_").lower()


def test_the_public_names_are_the_trees_fields() -> None:
    """A new setting joins :data:`ENVIRONMENT`; a renamed or removed one fails here."""
    assert {f"DEXLAB_{field.upper()}" for field in Settings.model_fields} == set(ENVIRONMENT)


def test_the_tree_is_every_section() -> None:
    fields = set(Settings.model_fields)
    for section in SECTIONS:
        assert issubclass(Settings, section)
        assert set(section.model_fields) <= fields
    assert set().union(*(s.model_fields for s in SECTIONS)) == fields


@pytest.mark.parametrize("name", sorted(ENVIRONMENT))
def test_each_environment_variable_sets_its_field(
    name: str, clean_environment: pytest.MonkeyPatch
) -> None:
    raw, expected = ENVIRONMENT[name]
    field = field_of(name)
    assert getattr(Settings(), field) != expected, "pick a value other than the default"
    clean_environment.setenv(name, raw)
    assert getattr(Settings(), field) == expected
    clean_environment.setenv(name.lower(), raw)  # names are not case-sensitive
    clean_environment.delenv(name)
    assert getattr(Settings(), field) == expected


def test_every_variable_at_once(clean_environment: pytest.MonkeyPatch) -> None:
    for name, (raw, _) in ENVIRONMENT.items():
        clean_environment.setenv(name, raw)
    settings = Settings()
    assert {name: getattr(settings, field_of(name)) for name in ENVIRONMENT} == {
        name: expected for name, (_, expected) in ENVIRONMENT.items()
    }


def test_options_win_over_the_environment(clean_environment: pytest.MonkeyPatch) -> None:
    clean_environment.setenv("DEXLAB_PORT", "9000")
    clean_environment.setenv("DEXLAB_WORKERS", "7")
    settings = Settings(port=8001)
    assert (settings.port, settings.workers) == (8001, 7)


def test_other_dexlab_variables_are_not_settings(clean_environment: pytest.MonkeyPatch) -> None:
    """The client's ``DEXLAB_URL`` may be set where the server runs; an unknown option
    given in code is a mistake."""
    clean_environment.setenv("DEXLAB_URL", "http://elsewhere:8000")
    clean_environment.setenv("DEXLAB_API_KEY", SECRET)
    assert Settings().port == 8000
    with pytest.raises(ValidationError, match="url"):
        Settings(url="http://elsewhere:8000")  # type: ignore[call-arg]


def test_a_refused_setting_is_named_not_echoed(clean_environment: pytest.MonkeyPatch) -> None:
    clean_environment.setenv("DEXLAB_API_KEYS", "alice:short-secret")
    with pytest.raises(ValidationError, match="api_keys") as error:
        Settings()
    assert "short-secret" not in str(error.value)


def test_the_sections_read_no_environment(clean_environment: pytest.MonkeyPatch) -> None:
    """Only the tree reads ``DEXLAB_*``: a section made anywhere else has its defaults."""
    defaults = {section: section() for section in SECTIONS}
    for name, (raw, _) in ENVIRONMENT.items():
        clean_environment.setenv(name, raw)
    for section, default in defaults.items():
        assert section() == default


def test_a_pool_process_gets_the_worker_section_only(clean_environment: pytest.MonkeyPatch) -> None:
    """What the pool hands a spawned process (worker.pool): the worker fields, no secret."""
    for name, (raw, _) in ENVIRONMENT.items():
        clean_environment.setenv(name, raw)
    settings = Settings()
    data = settings.model_dump(mode="json", include=set(WorkerSettings.model_fields))
    assert "api_keys" not in data and "session_secret" not in data
    received = WorkerSettings.model_validate(data)
    assert received.model_dump() == {f: getattr(settings, f) for f in WorkerSettings.model_fields}


def test_the_app_reads_no_environment(
    tmp_path: Path, clean_environment: pytest.MonkeyPatch
) -> None:
    """``create_app`` takes the tree its entry point built; what the environment says
    afterwards changes nothing (``/metrics``, the pages' directory)."""
    settings = Settings(data_dir=tmp_path, workers=0, docs_dir=tmp_path)
    clean_environment.setenv("DEXLAB_METRICS", "0")
    clean_environment.setenv("DEXLAB_DOCS_DIR", "/nowhere")
    app = create_app(settings)
    assert "/metrics" in app.openapi()["paths"]
    assert app.state.pages.settings.docs_dir == tmp_path
