"""Hardware backends for SourceBots boards."""

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend

__all__ = ["SBArduino2024HardwareBackend", "SBArduinoHardwareBackend"]
