"""sr-robot3's KCH (the Raspberry Pi's HAT): three user RGB LEDs, on j5aio's KCH board."""

from __future__ import annotations

from enum import IntEnum, unique
from typing import TYPE_CHECKING

from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.errors import CommunicationError

if TYPE_CHECKING:
    from j5aio.sync import RGBLED, KCHBoard

__all__ = ["KCH", "LED", "Colour", "UserLED"]



@unique
class UserLED(IntEnum):
    """The user LEDs, A to C."""

    A = 0
    B = 1
    C = 2


class Colour:
    """Colours of a user LED: which of red, green and blue are lit."""

    OFF = (False, False, False)
    RED = (True, False, False)
    YELLOW = (True, True, False)
    GREEN = (False, True, False)
    CYAN = (False, True, True)
    BLUE = (False, False, True)
    MAGENTA = (True, False, True)
    WHITE = (True, True, True)


def _check_colour(value: object) -> tuple[bool, bool, bool]:
    if not isinstance(value, (tuple, list)) or len(value) != 3:
        raise ValueError("The LED requires 3 values for it's colour")
    red, green, blue = value
    return bool(red), bool(green), bool(blue)


class LED:
    """A user LED that does nothing: the robot has no KCH (not on a Raspberry Pi)."""

    __slots__ = ()

    @property
    def r(self) -> bool:
        """Whether red is lit."""
        return self.colour[0]

    @r.setter
    def r(self, value: bool) -> None:
        colour = self.colour
        self.colour = (bool(value), colour[1], colour[2])

    @property
    def g(self) -> bool:
        """Whether green is lit."""
        return self.colour[1]

    @g.setter
    def g(self, value: bool) -> None:
        colour = self.colour
        self.colour = (colour[0], bool(value), colour[2])

    @property
    def b(self) -> bool:
        """Whether blue is lit."""
        return self.colour[2]

    @b.setter
    def b(self, value: bool) -> None:
        colour = self.colour
        self.colour = (colour[0], colour[1], bool(value))

    @property
    def colour(self) -> tuple[bool, bool, bool]:
        """Which of red, green and blue are lit (a :class:`Colour`)."""
        return False, False, False

    @colour.setter
    def colour(self, value: tuple[bool, bool, bool]) -> None:
        _check_colour(value)


class KCHLED(LED):
    """A user LED of the KCH.

    :param led: j5aio's RGB LED (its colours are duty cycles: lit is 1, dark 0).
    """

    __slots__ = ("_led",)

    def __init__(self, led: RGBLED) -> None:
        self._led = led

    @property
    def colour(self) -> tuple[bool, bool, bool]:
        """Which of red, green and blue are lit (a :class:`Colour`)."""
        try:
            red, green, blue = self._led.colour
        except CommunicationError as error:
            raise disconnected(error) from error
        return red > 0, green > 0, blue > 0

    @colour.setter
    def colour(self, value: tuple[bool, bool, bool]) -> None:
        red, green, blue = _check_colour(value)
        try:
            self._led.colour = (float(red), float(green), float(blue))
        except CommunicationError as error:
            raise disconnected(error) from error


class KCH:
    """The KCH, with its user LEDs (which do nothing on a computer without one).

    :param board: j5aio's KCH board, or ``None`` when the robot has none.
    """

    __slots__ = ("_board", "_leds")

    def __init__(self, board: KCHBoard | None = None) -> None:
        self._board = board
        self._leds: tuple[LED, ...] = (
            tuple(KCHLED(led) for led in board.leds)
            if board is not None
            else tuple(LED() for _ in UserLED)
        )

    @property
    def leds(self) -> tuple[LED, ...]:
        """The user LEDs, by :class:`UserLED` (``kch.leds[LED_A]``)."""
        return self._leds
