"""Arduino boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.arduino.uno import AnaloguePin, ArduinoUno, PinNumber

__all__ = ["AnaloguePin", "ArduinoUno", "PinNumber"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.arduino.uno": ["AnaloguePin", "ArduinoUno", "PinNumber"],
        },
    )
