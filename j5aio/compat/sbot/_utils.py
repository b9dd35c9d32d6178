"""sbot's ``utils``: finding the boards, waiting for the start, sleeping and the buzzer."""

from __future__ import annotations

import logging
import time
from datetime import timedelta
from enum import IntEnum

from ._checks import float_bounds_check
from ._comp import Comp
from ._errors import translate_errors, watch_match
from ._kit import KitLink
from .game_specific import GAME_LENGTH

__all__ = ["GAME_LENGTH", "Note", "Utils"]

LOGGER = logging.getLogger("sbot._utils")


def _wait_again() -> None:
    """Wait for the start once more, signalling on the boards as the first wait did."""
    from j5aio.competition.start import wait_for_start
    from j5aio.robot import BaseRobot
    from j5aio.sync.wrapping import call

    call(wait_for_start, BaseRobot.boards(), None)


class Note(IntEnum):
    """Notes in scientific pitch notation, by their frequencies in Hz."""

    C6 = 1047
    D6 = 1175
    E6 = 1319
    F6 = 1397
    G6 = 1568
    A6 = 1760
    B6 = 1976
    C7 = 2093
    D7 = 2349
    E7 = 2637
    F7 = 2794
    G7 = 3136
    A7 = 3520
    B7 = 3951
    C8 = 4186


@translate_errors
class Utils:
    """The robot as a whole: its boards, its start, its time and its buzzer.

    :param boards: the kit.
    :param comp: the match's metadata, loaded at the start.
    """

    __slots__ = ("_boards", "_comp")

    def __init__(self, boards: KitLink, comp: Comp) -> None:
        self._boards = boards
        self._comp = comp

    def sleep(self, duration: float) -> None:
        """Wait ``duration`` seconds (robot seconds, on a simulated kit run faster).

        :raises ValueError: ``duration`` is negative.
        """
        if self._boards.loaded:
            self._boards.robot.sleep(duration)
            return
        if duration < 0:
            raise ValueError("sleep length must be non-negative")
        time.sleep(duration)

    def wait_start(self) -> None:
        """Wait for the start button (finding the boards first if need be).

        The run LED flashes and the buzzer beeps while the robot waits. Once started,
        :attr:`Comp.zone` and :attr:`Comp.is_competition` are known and, in a match,
        the match timer runs: the program is stopped when the match ends. Called again,
        it waits for another press (the match, and its metadata, stay the first one's).
        """
        if not self._boards.loaded:
            self.load_boards()
        robot = self._boards.robot
        LOGGER.info("Waiting for start button.")
        if self._comp.loaded:
            _wait_again()
        else:
            robot.wait_start()
            self._comp._load(robot)
            timer = robot.match_timer
            if timer is not None:
                watch_match(timer)
        LOGGER.info("Start button pressed.")

    def sound_buzzer(self, frequency: int, duration: float) -> None:
        """Play ``frequency`` Hz for ``duration`` seconds on the power board's buzzer.

        Returns at once; a new note replaces one still playing.

        :raises TypeError: ``frequency`` or ``duration`` is not a number.
        :raises ValueError: ``frequency`` is outside 8 to 10 000 Hz, or ``duration`` is
            negative or too long.
        """
        piezo = self._boards.power_board().piezo
        frequency_int = int(float_bounds_check(
            frequency, 8, 10_000, "Frequency is a float in Hz between 0 and 10000"))
        duration_ms = int(float_bounds_check(
            duration * 1000, 0, 2**31 - 1,
            f"Duration is a float in seconds between 0 and {(2**31 - 1) / 1000:,.0f}"))
        piezo.buzz(timedelta(milliseconds=duration_ms), frequency_int)

    def load_boards(self) -> None:
        """Find the boards (``wait_start`` does it too if needed), and log what was found.

        :raises RuntimeError: the boards have been loaded already.
        """
        self._boards.load()
        self._boards.log_connected_boards()
