"""DEXLAB_API_KEYS: its format, its errors (which never show a secret), seeding."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest
from pydantic import ValidationError

from service.auth.seeding import DeclaredKey, parse_api_keys, seed_keys
from service.config import ServiceSettings
from worker.store import open_store

SECRET = "0123456789abcdefXYZ"


def test_entries_name_secret_and_an_admin_flag() -> None:
    keys = parse_api_keys(f" alice:{SECRET} , root:{SECRET}2:admin,,")
    assert keys == [DeclaredKey("alice", SECRET), DeclaredKey("root", SECRET + "2", True)]
    assert SECRET not in repr(keys)
    assert parse_api_keys("") == []


@pytest.mark.parametrize(
    ("value", "phrase"),
    [
        (f"alice{SECRET}", "entry 1 of DEXLAB_API_KEYS must be 'name:secret'"),
        (f"ok:{SECRET}1,bad name:{SECRET}", "entry 2 of DEXLAB_API_KEYS: The key name"),
        ("alice:short-secret", "The secret of key 'alice'"),
        (f"alice:{SECRET} x", "without spaces"),
        (f"alice:{SECRET},alice:{SECRET}1", "names the key 'alice' twice"),
        (f"alice:{SECRET},bob:{SECRET}", "gives key 'bob' another key's secret"),
    ],
)
def test_a_bad_value_is_refused_without_echoing_secrets(value: str, phrase: str) -> None:
    with pytest.raises(ValueError, match=phrase) as error:
        parse_api_keys(value)
    assert SECRET not in str(error.value)
    with pytest.raises(ValidationError) as settings_error:
        ServiceSettings(api_keys=value)
    assert SECRET not in str(settings_error.value) and "short-secret" not in str(
        settings_error.value
    )


def test_seeding_logs_names_never_secrets(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    try:
        with caplog.at_level(logging.INFO, logger="dexlab.service"):
            seed_keys(store, f"alice:{SECRET},root:{SECRET}1:admin")
            seed_keys(store, f"alice:{SECRET}")
        assert [(k.name, k.admin) for k in store.api_keys()] == [
            ("alice", False),
            ("root", True),
        ]
    finally:
        store.close()
    assert "'alice' created" in caplog.text and "'alice' unchanged" in caplog.text
    assert SECRET not in caplog.text


def test_session_secret_and_cors_origins_are_checked() -> None:
    with pytest.raises(ValidationError, match="at least 32 characters"):
        ServiceSettings(session_secret="short")
    with pytest.raises(ValidationError, match="scheme://host"):
        ServiceSettings(cors_origins="https://a.example/path")
    settings = ServiceSettings(cors_origins="https://a.example, http://b.example:3000/")
    assert ServiceSettings.origin_list(settings.cors_origins) == [
        "https://a.example",
        "http://b.example:3000",
    ]
