"""Arduino boards."""

from j5aio.boards.arduino.uno import AnaloguePin, ArduinoUno, PinNumber

__all__ = ["AnaloguePin", "ArduinoUno", "PinNumber"]
