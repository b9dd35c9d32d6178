"""j5aio: an asyncio-native robotics API for school robotics competitions.

The async core lives here; a synchronous face for first-time students is in
:mod:`j5aio.sync`.
"""

from j5aio.backends.backend import Backend
from j5aio.backends.environment import Environment
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.errors import (
    BadGPIOPinModeError,
    BoardDisconnectionError,
    CommunicationError,
    NotSupportedByComponentError,
    NotSupportedByHardwareError,
    UnableToObtainLock,
)
from j5aio.robot import BaseRobot

__version__ = "0.1.0"

__all__ = [
    "Backend",
    "BadGPIOPinModeError",
    "BaseRobot",
    "Board",
    "BoardDisconnectionError",
    "BoardGroup",
    "CommunicationError",
    "Environment",
    "NotSupportedByComponentError",
    "NotSupportedByHardwareError",
    "UnableToObtainLock",
    "__version__",
]
