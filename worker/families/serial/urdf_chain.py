"""A URDF's chain from ``base_link`` to ``tip_link`` as a :class:`~.arm.SerialArm`.

Parsed by yourdfpy from the text alone: no file or network access (meshes are not
loaded, ``package://`` references are never resolved, and a document declaring a DTD or
entities is refused before parsing).  Revolute, continuous (as revolute over
[-180°, 180°)), prismatic and fixed joints; URDF's defaults (axis (1, 0, 0), limits 0
when absent).  Fixed joints fold into the fixed transforms.  A problem is a
:class:`UrdfProblem` naming the joint or link.
"""

from __future__ import annotations

import io
import logging
from typing import Any

import numpy as np

from worker.families.serial.kinematics.arm import SerialArm

__all__ = ["MAX_URDF_BYTES", "UrdfProblem", "arm_from_urdf"]

#: The largest URDF accepted (bytes of UTF-8).
MAX_URDF_BYTES = 256 * 1024
_MOVABLE = ("revolute", "continuous", "prismatic")


class UrdfProblem(ValueError):
    """What is wrong with a URDF, in words a user can act on."""


def _parse(text: str) -> Any:
    # lazy: yourdfpy (lxml, trimesh) loads only when a URDF is validated
    import yourdfpy

    head = text[:4096]
    if "xmlns:xacro" in head or "<xacro:" in text:
        raise UrdfProblem("this is a xacro file: expand it to plain URDF first (e.g. `xacro "
                          "robot.urdf.xacro > robot.urdf`) and send that")  # fmt: skip
    if "<!DOCTYPE" in text or "<!ENTITY" in text:
        raise UrdfProblem("a URDF may not declare a DTD or entities")
    quiet = logging.getLogger("yourdfpy")
    level, quiet.level = quiet.level, logging.CRITICAL
    try:
        return yourdfpy.URDF.load(
            io.StringIO(text), build_scene_graph=False, build_collision_scene_graph=False,
            load_meshes=False, load_collision_meshes=False,
            filename_handler=lambda *_args, **_kwargs: "",
        ).robot  # fmt: skip
    except Exception as error:  # lxml or yourdfpy: the document is no URDF
        raise UrdfProblem(f"not a URDF document: {error}") from None
    finally:
        quiet.level = level


def _chain(robot: Any, base_link: str, tip_link: str) -> list[Any]:
    links = {link.name for link in robot.links}
    for role, name in (("base_link", base_link), ("tip_link", tip_link)):
        if name not in links:
            raise UrdfProblem(f"{role} {name!r} is no link of the URDF (links: "
                              f"{', '.join(sorted(links)[:20])})")  # fmt: skip
    into = {joint.child: joint for joint in robot.joints}
    chain: list[Any] = []
    link = tip_link
    while link != base_link:
        joint = into.get(link)
        if joint is None:
            raise UrdfProblem(f"tip_link {tip_link!r} does not descend from base_link "
                              f"{base_link!r}")  # fmt: skip
        chain.append(joint)
        link = joint.parent
        if len(chain) > len(robot.joints):
            raise UrdfProblem("the URDF's joints form a loop")
    return chain[::-1]


def arm_from_urdf(
    text: str,
    base_link: str,
    tip_link: str,
    base: np.ndarray | None = None,
    tool: np.ndarray | None = None,
    length_unit: str = "m",
) -> SerialArm:
    """The arm of the joints from ``base_link`` to ``tip_link``."""
    if len(text.encode()) > MAX_URDF_BYTES:
        raise UrdfProblem(f"the URDF is {len(text.encode()):,} bytes; at most "
                          f"{MAX_URDF_BYTES:,}")  # fmt: skip
    chain = _chain(_parse(text), base_link, tip_link)
    fixed = [np.eye(4) if base is None else np.asarray(base, dtype=float)]
    axes, prismatic, lower, upper, names = [], [], [], [], []
    for joint in chain:
        origin = np.eye(4) if joint.origin is None else np.asarray(joint.origin, dtype=float)
        if joint.mimic is not None:
            raise UrdfProblem(f"joint {joint.name!r} mimics another: mimic joints are not "
                              "supported")  # fmt: skip
        if joint.type == "fixed":
            fixed[-1] = fixed[-1] @ origin
            continue
        if joint.type not in _MOVABLE:
            raise UrdfProblem(f"joint {joint.name!r} is {joint.type}: only revolute, "
                              "continuous, prismatic and fixed joints are supported")  # fmt: skip
        fixed[-1] = fixed[-1] @ origin
        fixed.append(np.eye(4))
        axis = np.asarray(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), float)
        norm = float(np.linalg.norm(axis))
        if not norm > 0.0:
            raise UrdfProblem(f"joint {joint.name!r} has a zero axis")
        axes.append(axis / norm)
        prismatic.append(joint.type == "prismatic")
        if joint.type == "continuous":
            lo, hi = -np.pi, np.pi
        else:
            limit = joint.limit
            lo = float(limit.lower or 0.0) if limit is not None else 0.0
            hi = float(limit.upper or 0.0) if limit is not None else 0.0
        if hi < lo:
            raise UrdfProblem(f"joint {joint.name!r}: its lower limit {lo:g} exceeds its upper "
                              f"limit {hi:g}")  # fmt: skip
        lower.append(lo)
        upper.append(hi)
        names.append(str(joint.name))
    if tool is not None:
        fixed[-1] = fixed[-1] @ tool
    return SerialArm(
        fixed=np.stack(fixed),
        axes=np.reshape(np.asarray(axes, dtype=float), (-1, 3)),
        prismatic=np.asarray(prismatic, dtype=bool),
        lower=np.asarray(lower, dtype=float),
        upper=np.asarray(upper, dtype=float),
        names=tuple(names),
        length_unit=length_unit,
    )
