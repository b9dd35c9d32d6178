"""Console backends of the SourceBots boards."""

from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend

__all__ = ["SBArduinoConsoleBackend"]
