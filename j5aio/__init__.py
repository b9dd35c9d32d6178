"""j5aio: an asyncio-native robotics API for school robotics competitions.

The async core lives here; a synchronous face for first-time students is in
:mod:`j5aio.sync`.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
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

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.backend": ["Backend"],
            "j5aio.backends.environment": ["Environment"],
            "j5aio.boards.board": ["Board"],
            "j5aio.boards.board_group": ["BoardGroup"],
            "j5aio.errors": [
                "BadGPIOPinModeError",
                "BoardDisconnectionError",
                "CommunicationError",
                "NotSupportedByComponentError",
                "NotSupportedByHardwareError",
                "UnableToObtainLock",
            ],
            "j5aio.robot": ["BaseRobot"],
        },
    )
