"""Every setting an operator can give (each field of the settings tree, by its
environment name) is documented in the README, where operators look for them."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from pydantic_settings import BaseSettings

from service.config import Settings

ROOT = Path(__file__).resolve().parents[2]
#: The one class that reads the environment: the settings tree (all its sections).
SETTINGS: tuple[type[BaseSettings], ...] = (Settings,)


def test_every_settings_class_is_listed_here() -> None:
    """A new settings class must join :data:`SETTINGS` (so its fields are checked)."""
    defined = {
        match.group(1)
        for package in ("service", "worker", "dexlab")
        for path in (ROOT / package).rglob("*.py")
        for match in re.finditer(r"^class (\w+)\((?:.*, )?BaseSettings\b", path.read_text(), re.M)
    }
    assert defined == {cls.__name__ for cls in SETTINGS}


@pytest.mark.parametrize(
    "name",
    [
        f"{cls.model_config.get('env_prefix', '')}{field}".upper()
        for cls in SETTINGS
        for field in cls.model_fields
    ],
)
def test_each_setting_is_in_the_readme(name: str) -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert re.search(rf"`{name}\b", readme), f"{name} is not in the README"
