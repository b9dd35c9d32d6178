"""Console backends of the SourceBots boards."""

from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sb.arduino_2024 import SBArduino2024ConsoleBackend

__all__ = ["SBArduino2024ConsoleBackend", "SBArduinoConsoleBackend"]
