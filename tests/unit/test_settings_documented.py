"""Every setting an operator can give (each field of the settings tree, by its
environment name) is documented in docs/operations.md, the settings reference the
README links to."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from pydantic_settings import BaseSettings

from service.config import Settings

ROOT = Path(__file__).resolve().parents[2]
SETTINGS_REFERENCE = ROOT / "docs" / "operations.md"
#: The one class that reads the environment: the settings tree (all its sections).
SETTINGS: tuple[type[BaseSettings], ...] = (Settings,)


def test_every_settings_class_is_listed_here() -> None:
    """A new settings class must join :data:`SETTINGS` (so its fields are checked); one
    deriving from a class of the packages is found by tests/test_environment_reads.py."""
    defined = {
        match.group(1)
        for package in ("service", "worker", "dexlab")
        for path in (ROOT / package).rglob("*.py")
        for match in re.finditer(r"^class (\w+)\((?:.*, )?BaseSettings\b", path.read_text(), re.M)
    }
    assert defined == {cls.__name__ for cls in SETTINGS}


#: Where the project reads environment variables: the code, its tests, scripts and images.
ENVIRONMENT_READERS = ("service", "worker", "dexlab", "tests", "scripts", "bench", ".ci")
ENVIRONMENT_FILES = ("Dockerfile", "docker-compose.yml")


def documented_settings() -> str:
    """The "Settings" section of docs/operations.md: one table row per variable."""
    reference = SETTINGS_REFERENCE.read_text(encoding="utf-8")
    return reference.split("\n## Settings\n", 1)[1].split("\n## ", 1)[0]


def variables_in_code() -> set[str]:
    paths = [ROOT / name for name in ENVIRONMENT_FILES]
    for directory in ENVIRONMENT_READERS:
        paths += [p for p in (ROOT / directory).rglob("*") if p.is_file() and p.suffix != ".pyc"]
    return {
        name
        for path in paths
        if "vendor" not in path.parts
        for name in re.findall(r"\bDEXLAB_[A-Z0-9_]*[A-Z0-9]\b", path.read_text(errors="ignore"))
    }


@pytest.mark.parametrize(
    "name",
    sorted(
        {
            f"{cls.model_config.get('env_prefix', '')}{field}".upper()
            for cls in SETTINGS
            for field in cls.model_fields
        }
    ),
)
def test_each_setting_is_in_the_settings_reference(name: str) -> None:
    row = re.compile(rf"^\| `{name}`", re.M)
    assert row.search(documented_settings()), f"{name} has no row in docs/operations.md"


def test_every_environment_variable_is_in_the_settings_reference() -> None:
    """Variables read outside the settings classes too (the client's, the tests')."""
    names = variables_in_code()
    assert {"DEXLAB_URL", "DEXLAB_REQUIRE_SERVICES", "DEXLAB_STORE_URL"} <= names
    settings = documented_settings()
    missing = sorted(name for name in names if not re.search(rf"^\|.*`{name}`", settings, re.M))
    assert not missing, f"not in docs/operations.md's settings: {missing}"
