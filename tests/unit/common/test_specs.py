from __future__ import annotations

from typing import Annotated

import pytest
from pydantic import ValidationError

from worker.common.specs import FrozenSpec, GridSpecBase, entries


class Pair(FrozenSpec):
    values: Annotated[tuple[float, float], entries(2, "values needs two numbers")]


def test_frozen_forbids_extras_and_non_finite_floats() -> None:
    spec = Pair(values=(1.0, 2.0))
    with pytest.raises(ValidationError):
        spec.values = (3.0, 4.0)  # type: ignore[misc]
    with pytest.raises(ValidationError, match="extra"):
        Pair.model_validate({"values": [1, 2], "colour": "red"})
    with pytest.raises(ValidationError, match="finite"):
        Pair(values=(float("nan"), 1.0))


def test_entries_gives_one_message_for_a_wrong_length() -> None:
    with pytest.raises(ValidationError) as caught:
        Pair.model_validate({"values": [1, "x", 3]})
    errors = caught.value.errors()
    assert len(errors) == 1 and "values needs two numbers, not 3" in errors[0]["msg"]


def test_grid_bounds_must_be_ordered() -> None:
    assert GridSpecBase(bounds=(-1, 1, -2, 2)).points_per_axis == 201
    with pytest.raises(ValidationError, match="x_min 1 must be less than x_max 0"):
        GridSpecBase(bounds=(1, 0, 0, 1))
    with pytest.raises(ValidationError, match="y_min 3 must be less than y_max 3"):
        GridSpecBase(bounds=(0, 1, 3, 3))
    with pytest.raises(ValidationError, match="less than or equal to 2001"):
        GridSpecBase(points_per_axis=2002)
