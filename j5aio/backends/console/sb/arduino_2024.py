"""The console backend of the SourceBots Arduino running the sb2024 firmware."""

from __future__ import annotations

from j5aio.backends.console.arduino_ultrasound import ArduinoUltrasoundConsoleBackend
from j5aio.boards.sb.arduino_2024 import SBArduino2024Board

__all__ = ["SBArduino2024ConsoleBackend"]


class SBArduino2024ConsoleBackend(ArduinoUltrasoundConsoleBackend):
    """The SourceBots Arduino (sb2024) on the console: pins 2-19, the LED and ultrasound.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = SBArduino2024Board
