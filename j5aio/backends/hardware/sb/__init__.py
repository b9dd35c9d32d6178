"""Hardware backends for SourceBots boards."""

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend

__all__ = ["SBArduinoHardwareBackend"]
