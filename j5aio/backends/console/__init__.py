"""The console environment: boards that print what they do and ask for their readings.

Use it to see what a program would do without any hardware::

    from j5aio.backends.console import CONSOLE_ENVIRONMENT
    power_boards = await CONSOLE_ENVIRONMENT.get_board_group(PowerBoard)

``CONSOLE_ENVIRONMENT`` (from :mod:`.env`) is made on first use, from the registered
board kinds.
"""

from typing import TYPE_CHECKING, Any

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console

if TYPE_CHECKING:
    from j5aio.backends.console.env import CONSOLE_ENVIRONMENT

__all__ = ["CONSOLE_ENVIRONMENT", "Console", "ConsoleBackend"]


def __getattr__(name: str) -> Any:
    if name == "CONSOLE_ENVIRONMENT":
        from j5aio.backends.console.env import CONSOLE_ENVIRONMENT

        return CONSOLE_ENVIRONMENT
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
