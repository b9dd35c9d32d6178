"""The SourceBots servo board: the SR v4 Servo Board with SourceBots' firmware 4.4."""

from __future__ import annotations

from typing import ClassVar

from j5aio.boards.sr.v4.servo_board_fw4 import ServoBoardFw4

__all__ = ["SBServoBoard"]


class SBServoBoard(ServoBoardFw4):
    """The servo board of the SourceBots 2024+ kit: SourceBots' firmware 4.4, eight servos.

    The same board and protocol as :class:`~j5aio.boards.sr.v4.servo_board_fw4.ServoBoardFw4`,
    with eight servos (0 to 7) whose pulses may be as short as 300 µs. Positions -1 to 1
    give pulses of 350 to 1980 µs until a program sets other limits, as in sbot.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SourceBots Servo Board (firmware 4.4)"
    SERVO_COUNT: ClassVar[int] = 8
