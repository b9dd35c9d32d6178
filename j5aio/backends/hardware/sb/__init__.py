"""Hardware backends for SourceBots boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
    from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend

__all__ = ["SBArduino2024HardwareBackend", "SBArduinoHardwareBackend"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.hardware.sb.arduino": ["SBArduinoHardwareBackend"],
            "j5aio.backends.hardware.sb.arduino_2024": ["SBArduino2024HardwareBackend"],
        },
    )
