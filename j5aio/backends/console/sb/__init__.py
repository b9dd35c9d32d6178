"""Console backends of the SourceBots boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend as SBArduinoConsoleBackend
    from j5aio.backends.console.sb.arduino_2024 import (
        SBArduino2024ConsoleBackend as SBArduino2024ConsoleBackend,
    )

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.console.sb.arduino": ["SBArduinoConsoleBackend"],
            "j5aio.backends.console.sb.arduino_2024": ["SBArduino2024ConsoleBackend"],
        },
    )
