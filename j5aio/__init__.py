"""j5aio: an asyncio-native robotics API for school robotics competitions.

The async core lives here; a synchronous face for first-time students is in
:mod:`j5aio.sync`.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend as Backend
    from j5aio.backends.environment import Environment as Environment
    from j5aio.boards.board import Board as Board
    from j5aio.boards.board_group import BoardGroup as BoardGroup
    from j5aio.concurrency import at_once as at_once
    from j5aio.errors import BadGPIOPinModeError as BadGPIOPinModeError
    from j5aio.errors import BoardDisconnectionError as BoardDisconnectionError
    from j5aio.errors import CommunicationError as CommunicationError
    from j5aio.errors import NotSupportedByComponentError as NotSupportedByComponentError
    from j5aio.errors import NotSupportedByHardwareError as NotSupportedByHardwareError
    from j5aio.errors import UnableToObtainLock as UnableToObtainLock
    from j5aio.robot import BaseRobot as BaseRobot

__version__ = "0.1.0"

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.backend": ["Backend"],
            "j5aio.backends.environment": ["Environment"],
            "j5aio.boards.board": ["Board"],
            "j5aio.boards.board_group": ["BoardGroup"],
            "j5aio.concurrency": ["at_once"],
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
        own=("__version__",),
    )
