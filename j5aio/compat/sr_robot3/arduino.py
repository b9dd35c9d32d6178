"""sr-robot3's Arduino on j5aio's SR Arduino: pins 0-19, modes, reads in volts, ultrasound in mm."""

from __future__ import annotations

from enum import Enum, IntEnum
from typing import TYPE_CHECKING, Final

from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.compat.sr_robot3.utils import BoardIdentity
from j5aio.compat.units import volts_on_1023_scale, whole_millimetres
from j5aio.components.gpio_pin import GPIOPinMode as CoreMode
from j5aio.errors import CommunicationError, NotSupportedByHardwareError
from j5aio.sync import AllDigitalUno, Ruggeduino, SBArduinoBoard
from j5aio.sync.wrapping import call, unwrap

if TYPE_CHECKING:
    from j5aio.sync import ArduinoUno, GPIOPin

__all__ = ["AnalogPins", "Arduino", "GPIOPinMode", "Pin"]


class GPIOPinMode(str, Enum):  # noqa: UP042 - prints as sr-robot3's does
    """The modes of an Arduino pin."""

    INPUT = "INPUT"
    INPUT_PULLUP = "INPUT_PULLUP"
    OUTPUT = "OUTPUT"


class AnalogPins(IntEnum):
    """The analogue pins, numbered after the digital ones."""

    A0 = 14
    A1 = 15
    A2 = 16
    A3 = 17
    A4 = 18
    A5 = 19


_FIRST_ANALOGUE: Final = 14
_PIN_COUNT: Final = 20


class Pin:
    """One pin of the Arduino.

    sr-robot3 remembers a pin's mode itself (the board does not report it); so does this
    class, and it puts j5aio's pin in the matching mode when a read needs one.

    :param pin: j5aio's pin, or ``None`` for pins 0 and 1 (the serial link).
    :param index: the pin's number.
    """

    __slots__ = ("_core_mode", "_core_pin", "_index", "_mode", "_pin")

    def __init__(self, pin: GPIOPin | None, index: int) -> None:
        self._pin = pin
        self._core_pin = unwrap(pin)  # (its coroutines, called through the facade's runtime)
        self._index = index
        self._mode = GPIOPinMode.INPUT
        self._core_mode: CoreMode | None = None  # (None: ask j5aio's pin)

    @property
    def _supports_analog(self) -> bool:
        return self._index >= _FIRST_ANALOGUE

    def _core(self) -> GPIOPin:
        if self._pin is None:
            raise OSError("This pin cannot be controlled.")
        return self._pin

    def _check_if_disabled(self) -> None:
        self._core()

    def _put_in(self, pin: GPIOPin, mode: CoreMode) -> None:
        """Put j5aio's pin in ``mode`` unless it is known to be in it already."""
        if self._core_mode is None:
            current = pin.mode
            self._core_mode = current if isinstance(current, CoreMode) else None
        if self._core_mode is not mode:
            pin.mode = mode
            self._core_mode = mode

    def _forget_core_mode(self) -> None:
        """The firmware changed the pin's mode by itself (an ultrasound measurement)."""
        self._core_mode = None

    @property
    def mode(self) -> GPIOPinMode:
        """The pin's mode (``INPUT`` until set); setting it tells the board.

        :raises OSError: the pin is 0 or 1 (the serial link), or the mode set is not a
            :class:`GPIOPinMode`.
        """
        self._core()
        return self._mode

    @mode.setter
    def mode(self, value: GPIOPinMode) -> None:
        pin = self._core()
        if not isinstance(value, GPIOPinMode):
            raise OSError("Pin mode only supports being set to a GPIOPinMode")
        if value is GPIOPinMode.OUTPUT:
            core_mode = CoreMode.DIGITAL_OUTPUT
        elif value is GPIOPinMode.INPUT_PULLUP:
            core_mode = CoreMode.DIGITAL_INPUT_PULLUP
        elif self._supports_analog:
            core_mode = CoreMode.ANALOGUE_INPUT  # (an input that reads volts too)
        else:
            core_mode = CoreMode.DIGITAL_INPUT
        try:
            pin.mode = core_mode
        except CommunicationError as error:
            raise disconnected(error) from error
        self._core_mode = core_mode
        self._mode = value

    def digital_read(self) -> bool:
        """Read the pin's level (an output gives the level it drives).

        :raises OSError: the pin is 0 or 1.
        """
        pin = self._core()
        try:
            if self._mode is GPIOPinMode.OUTPUT:
                self._put_in(pin, CoreMode.DIGITAL_OUTPUT)
                return pin.last_digital_write
            wanted = (
                CoreMode.DIGITAL_INPUT_PULLUP
                if self._mode is GPIOPinMode.INPUT_PULLUP
                else CoreMode.DIGITAL_INPUT
            )
            self._put_in(pin, wanted)
            level: bool = call(self._core_pin.digital_read)
        except CommunicationError as error:
            raise disconnected(error) from error
        return level

    def digital_write(self, value: bool) -> None:
        """Drive an output pin high (true) or low (false).

        :raises OSError: the pin is not an ``OUTPUT``, or is 0 or 1.
        """
        pin = self._core()
        if self._mode is not GPIOPinMode.OUTPUT:
            raise OSError(f"Digital write is not supported in {self._mode}")
        try:
            self._put_in(pin, CoreMode.DIGITAL_OUTPUT)
            call(self._core_pin.digital_write, bool(value))
        except CommunicationError as error:
            raise disconnected(error) from error

    def analog_read(self) -> float:
        """Read the voltage on an analogue pin (A0 to A5), 0 to 5 V.

        :raises OSError: the pin is not in ``INPUT`` mode, is not analogue, or is 0 or 1.
        """
        pin = self._core()
        if self._mode is not GPIOPinMode.INPUT:
            raise OSError(f"Analog read is not supported in {self._mode}")
        if not self._supports_analog:
            raise OSError("Pin does not support analog read")
        try:
            self._put_in(pin, CoreMode.ANALOGUE_INPUT)
            volts: float = call(self._core_pin.analogue_read)
        except CommunicationError as error:
            raise disconnected(error) from error
        return volts_on_1023_scale(volts)

    def __repr__(self) -> str:
        return (
            f"<{type(self).__qualname__} index={self._index} analog={self._supports_analog} "
            f"disabled={self._pin is None}>"
        )


class Arduino:
    """An Arduino, as sr-robot3 shows it.

    :param board: j5aio's Arduino (the SR Arduino on the 2023+ kit).
    """

    __slots__ = ("_board", "_pins")

    def __init__(self, board: ArduinoUno) -> None:
        self._board = board
        core_pins = board.pins
        self._pins = tuple(
            Pin(core_pins.get(index), index)
            for index in range(_PIN_COUNT)
        )

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``Arduino``."""
        return "Arduino"

    @property
    def pins(self) -> tuple[Pin, ...]:
        """The pins, 0 to 19 (0 and 1 carry the serial link and cannot be used)."""
        return self._pins

    def identify(self) -> BoardIdentity:
        """The board's identity; its asset tag is the USB serial number."""
        firmware = self._board.firmware_version or ""
        return BoardIdentity(
            "Student Robotics", "SRduino", self._board.serial_number, firmware,
        )

    def command(self, command: str) -> str:
        """Send ``command`` to the firmware as it is and return its first reply line.

        :raises OSError: this Arduino's firmware takes no raw commands.
        """
        board = self._board
        if not isinstance(board, Ruggeduino):
            raise OSError(f"{board.name} does not take raw commands")
        try:
            return board.command(command)
        except NotSupportedByHardwareError as error:
            raise OSError(str(error)) from error
        except CommunicationError as error:
            raise disconnected(error) from error

    def map_pin_number(self, pin_number: int) -> str:
        """The character a pin is sent as (pin 0 is ``a``).

        :raises ValueError: the pin is not one of 2 to 19.
        """
        try:
            self.pins[pin_number]._check_if_disabled()
        except (IndexError, TypeError, OSError):
            raise ValueError("Invalid pin provided") from None
        return chr(pin_number + ord("a"))

    def ultrasound_measure(self, pulse_pin: int, echo_pin: int) -> int:
        """Measure a distance with an ultrasound sensor: millimetres, 0 with no echo.

        :param pulse_pin: the pin wired to the sensor's trigger.
        :param echo_pin: the pin wired to its echo.
        :raises ValueError: a pin is not one of 2 to 19.
        """
        try:
            self.map_pin_number(pulse_pin)
        except ValueError:
            raise ValueError("Invalid pulse pin provided") from None
        try:
            self.map_pin_number(echo_pin)
        except ValueError:
            raise ValueError("Invalid echo pin provided") from None
        board = self._board
        if not isinstance(board, (AllDigitalUno, SBArduinoBoard)):
            raise OSError(f"{board.name} cannot measure with an ultrasound sensor")
        try:
            metres = board.ultrasound_sensors[pulse_pin, echo_pin].distance()
        except CommunicationError as error:
            raise disconnected(error) from error
        finally:
            self._pins[pulse_pin]._forget_core_mode()
            self._pins[echo_pin]._forget_core_mode()
        return whole_millimetres(metres)

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._board!r}>"
