"""The robot's mode, as sr-robot3 names it (its values come from j5aio's match metadata)."""

from __future__ import annotations

from enum import Enum

from j5aio.competition.metadata import Mode

__all__ = ["RobotMode", "robot_mode"]


class RobotMode(Enum):
    """Whether the robot is in a match (``COMP``) or being developed (``DEV``)."""

    COMP = "COMP"
    DEV = "DEV"


def robot_mode(mode: Mode) -> RobotMode:
    """The :class:`RobotMode` of j5aio's :class:`~j5aio.competition.metadata.Mode`."""
    return RobotMode(mode.value)
