"""sbot's ``leds``: the three user RGB LEDs of the brain's HAT, eight colours each."""

from __future__ import annotations

from enum import Enum

from ._errors import translate_errors
from ._kit import KitLink

__all__ = ["Colour", "Led"]


class Colour(Enum):
    """The colours of a user LED: red, green and blue each on or off."""

    OFF = (False, False, False)
    RED = (True, False, False)
    YELLOW = (True, True, False)
    GREEN = (False, True, False)
    CYAN = (False, True, True)
    BLUE = (False, False, True)
    MAGENTA = (True, False, True)
    WHITE = (True, True, True)


@translate_errors
class Led:
    """The user LEDs 0, 1 and 2.

    On a robot with the HAT (j5aio's ``robot.kch``) they light; on one without, as with
    sbot, setting a colour does nothing and every LED reads :attr:`Colour.OFF`.

    :param boards: the kit the LEDs are found on.
    """

    __slots__ = ("_boards",)

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards

    def set_colour(self, id: int, colour: Colour) -> None:
        """Light user LED ``id`` in ``colour``.

        :raises ValueError: ``id`` is not 0, 1 or 2.
        """
        self._validate_id(id)
        kch = self._boards.robot.kch if self._boards.loaded else None
        if kch is not None:
            red, green, blue = colour.value
            kch.leds[id].colour = (float(red), float(green), float(blue))

    def get_colour(self, id: int) -> Colour:
        """Return the colour of user LED ``id``.

        :raises ValueError: ``id`` is not 0, 1 or 2.
        """
        self._validate_id(id)
        kch = self._boards.robot.kch if self._boards.loaded else None
        if kch is None:
            return Colour.OFF
        red, green, blue = kch.leds[id].colour
        return Colour((red > 0, green > 0, blue > 0))

    @staticmethod
    def _validate_id(id: int) -> None:
        if id not in range(3):
            raise ValueError(f"Invalid LED ID: {id}")
