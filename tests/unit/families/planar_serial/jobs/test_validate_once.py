"""Validate once, pass objects on (issue 27): a planar3r-dexterity-map job checks its
links when its inputs are validated, keeps them as one frozen :class:`Arm`, and its
kinematics trust it (67 link checks in one job before)."""

from __future__ import annotations

from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext
from worker.families.planar_serial.kinematics import inputs
from worker.families.planar_serial.kinematics.inputs import Arm
from worker.registry import default_registry
from worker.submission import validate_inputs

MAP = default_registry().get("planar3r-dexterity-map")


def count_link_checks(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """A list whose length counts the link checks made from now on."""
    calls: list[int] = []
    real = inputs.checked_array

    def counting(value: Any, name: str, *args: Any, **kwargs: Any) -> Any:
        if name == "links":
            calls.append(1)
        return real(value, name, *args, **kwargs)

    monkeypatch.setattr(inputs, "checked_array", counting)
    return calls


@pytest.mark.parametrize(("example", "plots"), [(0, True), (1, False)])
def test_one_job_checks_its_links_at_most_three_times(
    monkeypatch: pytest.MonkeyPatch, example: int, plots: bool
) -> None:
    """Example 1 with its figures, and under joint limits."""
    assert MAP is not None
    spec = validate_inputs(MAP, {**MAP.examples[example].inputs, "plots": plots})
    assert isinstance(spec.links, Arm)  # type: ignore[attr-defined]
    calls = count_link_checks(monkeypatch)
    outcome = MAP.run(spec, RecordingContext())
    assert outcome.result["links"] == list(MAP.examples[example].inputs["links"])
    assert len(calls) <= 3


def test_the_kinematics_still_check_what_they_are_not_given_as_an_arm(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from worker.families.planar_serial.kinematics import full_dexterity_bands

    calls = count_link_checks(monkeypatch)
    assert full_dexterity_bands(Arm(15.0, 14.0, 8.0)) == full_dexterity_bands((15, 14, 8))
    assert len(calls) == 1
    with pytest.raises(ValueError, match="'links' parameter of full_dexterity_bands"):
        full_dexterity_bands((15, -14, 8))


@pytest.mark.parametrize(
    ("process_id", "change"),
    [("planar3r-synthesis", {}),
     ("planar3r-design", {"max_generations": 3, "population_size": 5, "starts": 2})],
)  # fmt: skip
def test_the_other_jobs_trust_their_links_too(
    monkeypatch: pytest.MonkeyPatch, process_id: str, change: dict[str, Any]
) -> None:
    """The synthesised links are an Arm, and the design search's candidates lie in
    their validated bounds: neither job checks links in its kinematics."""
    process = default_registry().get(process_id)
    assert process is not None
    spec = validate_inputs(process, {**process.examples[0].inputs, "plots": False, **change})
    calls = count_link_checks(monkeypatch)
    process.run(spec, RecordingContext())
    assert len(calls) <= 3


@pytest.mark.parametrize("example", [0, 1])
def test_one_job_finds_the_full_dexterity_bands_once(
    monkeypatch: pytest.MonkeyPatch, example: int
) -> None:
    """The unlimited arm's bands feed the regions, areas, notes and figures: found once
    and passed on (four or five times per job before)."""
    from worker.families.planar_serial import kinematics

    assert MAP is not None
    spec = validate_inputs(MAP, {**MAP.examples[example].inputs, "plots": True})
    calls: list[int] = []
    real = kinematics.full_dexterity_bands

    def counting(links: Any) -> Any:
        calls.append(1)
        return real(links)

    monkeypatch.setattr(kinematics, "full_dexterity_bands", counting)
    MAP.run(spec, RecordingContext())
    assert len(calls) == 1
