from __future__ import annotations

import numpy as np

from worker.common.parameter_errors import bad_parameter


def test_names_parameter_function_requirement_and_value() -> None:
    error = bad_parameter("links", "exact_orientation_dexterity", "three positive lengths",
                          (1, -2, 3))  # fmt: skip
    assert isinstance(error, ValueError)
    assert str(error) == (
        "The 'links' parameter of exact_orientation_dexterity must be three positive "
        "lengths. Got (1, -2, 3) instead."
    )


def test_long_arrays_are_shown_by_their_shape() -> None:
    error = bad_parameter("points", "f", "finite", np.zeros((50, 2)))
    assert str(error).endswith("Got an array of shape (50, 2) instead.")


def test_long_ragged_values_are_cut() -> None:
    ragged = [[1.0] * 30, [2.0]]
    shown = str(bad_parameter("points", "f", "finite", ragged)).split("Got ")[1]
    assert shown.endswith("... instead.") and len(shown) == 80 + len(" instead.")
