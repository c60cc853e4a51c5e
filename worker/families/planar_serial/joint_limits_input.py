"""The ``joint_limits_deg`` input of the planar3r jobs: its type, its text in the
published schema, and its checks (docs/methods/planar-serial.md, "Conventions")."""

from __future__ import annotations

__all__ = [
    "JOINT_LIMITS_DESCRIPTION",
    "RADIANS_LOOKALIKE",
    "JointLimitsDeg",
    "checked_joint_limits_deg",
]

#: [[lo, hi], [lo, hi], [lo, hi]] in degrees, joints 1..3.
JointLimitsDeg = tuple[tuple[float, float], tuple[float, float], tuple[float, float]]

#: Limits whose every value lies within +-2 pi (rounded up) were typed in radians: as
#: degrees, [[-2.618, 2.618], ...] would lock every joint within 3° of 0 and map
#: nothing.  They are refused by this static check, before anything is computed.
RADIANS_LOOKALIKE = 6.2832

JOINT_LIMITS_DESCRIPTION = (
    "Joint limits [[lo, hi], [lo, hi], [lo, hi]] in degrees for joints 1..3, with "
    "-180 <= lo <= hi <= 180; joint angles are wrapped to (-180, 180]. Limits whose every "
    f"value lies within ±2π ({RADIANS_LOOKALIKE:g}) are refused as radians. Omit for fully "
    "revolute joints (the exact closed form is then used)."
)


def checked_joint_limits_deg(limits: JointLimitsDeg | None) -> JointLimitsDeg | None:
    """The limits, or a ValueError naming joint_limits_deg: radians, a value outside
    [-180, 180], a lower limit above its upper one."""
    if limits is not None and all(abs(v) <= RADIANS_LOOKALIKE for pair in limits for v in pair):
        raise ValueError(
            "joint_limits_deg: degrees expected; these look like radians (every value lies "
            f"within ±2π = {RADIANS_LOOKALIKE:g}): give the limits in degrees, e.g. "
            "[[-150, 150], [-150, 150], [-175, 175]]"
        )
    for index, (lo, hi) in enumerate(limits or ()):
        for name, value in (("lower", lo), ("upper", hi)):
            if not -180.0 <= value <= 180.0:
                raise ValueError(
                    f"joint_limits_deg[{index}]: {name} limit {value:g} is outside [-180, 180]"
                )
        if lo > hi:
            raise ValueError(
                f"joint_limits_deg[{index}]: lower limit {lo:g} exceeds upper limit {hi:g}"
            )
    return limits
