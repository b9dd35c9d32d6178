"""Arduino boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.arduino.uno import AnaloguePin as AnaloguePin
    from j5aio.boards.arduino.uno import ArduinoUno as ArduinoUno
    from j5aio.boards.arduino.uno import PinNumber as PinNumber

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.arduino.uno": ["AnaloguePin", "ArduinoUno", "PinNumber"],
        },
    )
