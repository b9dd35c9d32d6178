"""Console backends of the SourceBots boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
    from j5aio.backends.console.sb.arduino_2024 import SBArduino2024ConsoleBackend

__all__ = ["SBArduino2024ConsoleBackend", "SBArduinoConsoleBackend"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.console.sb.arduino": ["SBArduinoConsoleBackend"],
            "j5aio.backends.console.sb.arduino_2024": ["SBArduino2024ConsoleBackend"],
        },
    )
