"""The console environment: boards that print what they do and ask for their readings.

Use it to see what a program would do without any hardware::

    from j5aio.backends.console import CONSOLE_ENVIRONMENT
    power_boards = await CONSOLE_ENVIRONMENT.get_board_group(PowerBoard)
"""

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.backends.console.env import CONSOLE_ENVIRONMENT

__all__ = ["CONSOLE_ENVIRONMENT", "Console", "ConsoleBackend"]
