"""``dexlab run ... --robot FILE``: your own arm in place of the inputs' ``robot``.

``--robot`` takes a URDF (with ``--base-link`` and ``--tip-link``), a DH table (CSV,
with ``--convention``) or a JSON robot object (:mod:`dexlab.robot_files`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import wraps
from pathlib import Path
from typing import Any, Literal

import click

from dexlab.robot_files import robot_from_file

__all__ = ["RobotChoice", "robot_options"]


@dataclass(frozen=True)
class RobotChoice:
    """What the ``--robot`` options asked for (nothing when ``path`` is None)."""

    path: Path | None
    base_link: str | None
    tip_link: str | None
    convention: Literal["standard", "modified"]

    def applied(self, inputs: dict[str, Any]) -> dict[str, Any]:
        """``inputs`` with this arm as their ``robot`` (unchanged without ``--robot``)."""
        if self.path is None:
            if self.base_link or self.tip_link:
                raise click.UsageError("--base-link and --tip-link go with --robot FILE.")
            return inputs
        try:
            robot = robot_from_file(self.path, base_link=self.base_link,
                                    tip_link=self.tip_link, convention=self.convention)  # fmt: skip
        except (ValueError, OSError) as exc:
            raise click.BadParameter(str(exc), param_hint="'--robot'") from None
        return {**inputs, "robot": robot}


def robot_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add --robot, --base-link, --tip-link and --convention, passed on as one
    ``robot`` argument (a :class:`RobotChoice`)."""

    @click.option(
        "--robot",
        "robot_path",
        type=click.Path(exists=True, dir_okay=False, path_type=Path),
        metavar="FILE",
        help="Your arm: a URDF (.urdf/.xml), a DH table (.csv/.tsv/.txt: a header row a, "
        "alpha_deg, d[, theta_deg, type, lower, upper], then a row per joint) or a robot "
        "JSON; replaces the inputs' robot.",
    )
    @click.option("--base-link", metavar="LINK", help="The URDF link the chain starts at.")
    @click.option("--tip-link", metavar="LINK", help="The URDF link the chain ends at.")
    @click.option(
        "--convention",
        type=click.Choice(["standard", "modified"]),
        default="standard",
        show_default=True,
        help="The DH table's convention.",
    )
    @wraps(command)
    def wrapped(
        *args: Any,
        robot_path: Path | None,
        base_link: str | None,
        tip_link: str | None,
        convention: Literal["standard", "modified"],
        **kwargs: Any,
    ) -> Any:
        choice = RobotChoice(robot_path, base_link, tip_link, convention)
        return command(*args, robot=choice, **kwargs)

    return wrapped
