"""The console backend of the SR Arduino (firmware 2)."""

from __future__ import annotations

from j5aio.backends.console.arduino_ultrasound import ArduinoUltrasoundConsoleBackend
from j5aio.backends.console.sr.v4.ruggeduino import SRV4RuggeduinoConsoleBackend
from j5aio.boards.sr.v4.arduino import SRArduinoBoard

__all__ = ["SRArduinoConsoleBackend"]


class SRArduinoConsoleBackend(ArduinoUltrasoundConsoleBackend, SRV4RuggeduinoConsoleBackend):
    """The SR Arduino on the console: pins 2-19, the LED, ultrasound and string commands.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = SRArduinoBoard
