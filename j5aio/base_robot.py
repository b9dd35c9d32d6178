"""j5's name for the module of :class:`~j5aio.robot.BaseRobot`, kept for j5 programs.

``from j5aio.base_robot import BaseRobot`` is ``from j5aio.robot import BaseRobot``.
"""

from j5aio.errors import UnableToObtainLock
from j5aio.robot import BaseRobot

__all__ = ["BaseRobot", "UnableToObtainLock"]
