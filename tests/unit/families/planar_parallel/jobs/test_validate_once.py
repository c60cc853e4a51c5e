"""A planar2dof-conditioning-map job checks its robot once (issue 27): it builds one
:class:`~worker.families.planar_parallel.kinematics.Robot` from its validated inputs and
every kinematic call it makes trusts it (no architecture, mode, point or axis checks)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.jobs.conditioning_map import run_conditioning_map
from worker.families.planar_parallel.kinematics import isotropic, kappa_region, model
from worker.families.planar_parallel.specs import ConditioningMapSpec

CHECKS = [
    (model, "checked_mode"), (pp, "checked_mode"), (pp, "checked_points"),
    (pp, "_checked_arch"), (pp, "_checked_axis"), (kappa_region, "checked_mode"),
    (kappa_region, "checked_limit"), (isotropic, "checked_mode"),
]  # fmt: skip


@pytest.mark.parametrize(
    "inputs",
    [{"l2": 1.5, "architecture": "isotropic", "inverse_condition_limit": 0.5,
      "points": [[0.0, -1.5], [3.0, 3.0]], "grid": {"points_per_axis": 21}, "plots": False},
     {"actuation": "telescopic-leg", "e": 0.5, "working_mode": [1, 1],
      "inverse_condition_limit": 0.4, "points": [[0.2, -0.3]],
      "grid": {"points_per_axis": 21}, "plots": False}],
)  # fmt: skip
def test_one_robot_checked_once(inputs: dict[str, Any], monkeypatch: pytest.MonkeyPatch) -> None:
    calls: Counter[str] = Counter()

    def counting(name: str, check: Callable[..., Any]) -> Callable[..., Any]:
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            calls[name] += 1
            return check(*args, **kwargs)

        return wrapper

    for module, name in CHECKS:
        monkeypatch.setattr(module, name, counting(name, getattr(module, name)))
    spec = ConditioningMapSpec.model_validate(inputs)
    outcome = run_conditioning_map(spec, RecordingContext())
    assert outcome.result["w_kappa0"]["found"]
    assert outcome.result["points"][0]["reachable"]
    assert calls == Counter({"checked_mode": 1}), calls  # the Robot's, once
