"""What the two Arduino simulators share: the Uno's pins, its ultrasound echoes, its USB face.

An Arduino Uno reboots whenever the host opens its port (DTR is wired to reset) and is
powered by its USB cable. The bootloader needs about 1.5 s before the sketch listens.

Ultrasound sensors are part of the outside world: for a (trigger, echo) pin pair the
simulator holds the length of the echo pulse, in whole microseconds as ``pulseIn`` measures
it. Each firmware turns that into its own reply with its own formula and ``pulseIn``
timeout; :meth:`ArduinoBoardSimulator.set_ultrasound_distance` picks the shortest echo for
which *this* firmware reads the given distance (to the millimetre).
"""

from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar, NamedTuple

from .arduino_pins import ArduinoUnoPins, PinMode
from .base import SerialBoardSimulator

__all__ = ["ARDUINO_UNO_R3", "ArduinoBoardSimulator", "UsbIdentity"]


class UsbIdentity(NamedTuple):
    """What port discovery shows about a USB-serial adapter."""

    vid: int
    pid: int
    manufacturer: str | None
    product: str | None


#: A genuine Arduino Uno R3 (ATmega16U2 USB-serial): no product string.
ARDUINO_UNO_R3 = UsbIdentity(0x2341, 0x0043, "Arduino (www.arduino.cc)", None)


class ArduinoBoardSimulator(SerialBoardSimulator):
    """An Arduino Uno running some sketch: pins, ultrasound echoes, reboot on open."""

    baudrate: ClassVar[int] = 115_200
    boot_delay: ClassVar[float] = 1.5
    resets_on_open: ClassVar[bool] = True
    powered_by_usb: ClassVar[bool] = True
    #: The ``pulseIn`` timeout of the firmware's ultrasound command, in µs.
    ULTRASOUND_TIMEOUT_US: ClassVar[int]
    #: Roughly how many millimetres one µs of echo reads as (a search starting point).
    _MM_PER_US: ClassVar[float]

    def __init__(self, serial_number: str, *, usb_identity: UsbIdentity = ARDUINO_UNO_R3) -> None:
        super().__init__(
            serial_number,
            usb_vid=usb_identity.vid,
            usb_pid=usb_identity.pid,
            manufacturer=usb_identity.manufacturer,
            product=usb_identity.product,
        )
        #: The pin table, for direct inspection.
        self.pins = ArduinoUnoPins()
        self._echoes: dict[tuple[int, int], int] = {}

    # --- inspection ---

    def pin_mode(self, pin: int) -> PinMode:
        """The mode of ``pin`` (0-19)."""
        return self.pins.mode(pin)

    def pin_level(self, pin: int) -> bool:
        """The level the firmware reads on ``pin`` now (an output reads its own level)."""
        return self.pins.level(pin)

    def output_level(self, pin: int) -> bool:
        """The output latch of ``pin``: its driven level, or its pull-up when an input."""
        return self.pins.output_level(pin)

    # --- the outside world ---

    def set_input_level(self, pin: int, level: bool | None) -> None:
        """Drive ``pin`` HIGH (True) or LOW (False) from outside, or let it float (None)."""
        self.pins.set_input_level(pin, level)

    def set_analogue(self, pin: int, *, volts: float | None = None, raw: int | None = None) -> None:
        """Apply a voltage to analogue pin ``pin`` (14-19), in volts or as an ADC reading."""
        self.pins.set_analogue(pin, volts=volts, raw=raw)

    def set_ultrasound_echo(self, trigger: int, echo: int, microseconds: int | None) -> None:
        """Set the echo pulse a sensor on these pins returns, in µs (None: no echo)."""
        self.pins.check_pin(trigger)
        self.pins.check_pin(echo)
        if microseconds is None:
            self._echoes.pop((trigger, echo), None)
        elif microseconds < 0:
            raise ValueError("an echo cannot be shorter than 0 µs")
        else:
            self._echoes[(trigger, echo)] = microseconds

    def set_ultrasound_distance(self, trigger: int, echo: int, metres: float | None) -> None:
        """Put an object ``metres`` away from the sensor on these pins (None: nothing there).

        The echo becomes the shortest whole number of µs that this firmware reads as the
        distance rounded to a millimetre. Beyond the firmware's range the reading is 0.
        """
        if metres is None:
            self.set_ultrasound_echo(trigger, echo, None)
            return
        if metres < 0:
            raise ValueError("a distance cannot be negative")
        self.set_ultrasound_echo(trigger, echo, self._shortest_echo(round(metres * 1000)))

    def ultrasound_echo(self, trigger: int, echo: int) -> int | None:
        """The echo pulse in µs of the sensor on these pins (None: no echo)."""
        return self._echoes.get((trigger, echo))

    def _shortest_echo(self, millimetres: int) -> int:
        microseconds = max(0, int(millimetres / self._MM_PER_US) - 2)
        while (
            self._reading_mm(microseconds) < millimetres
            and microseconds <= self.ULTRASOUND_TIMEOUT_US
        ):
            microseconds += 1
        return microseconds

    # --- for the firmware ---

    def _fire_ultrasound(self, trigger: int, echo: int) -> int:
        """Pulse the trigger, listen on the echo pin; return what ``pulseIn`` measures.

        Pin side effects: the trigger ends as an OUTPUT driven LOW, the echo as an INPUT
        without pull-up (the same pin may be both, and then ends as an input).
        """
        self.pins.pin_mode(trigger, PinMode.OUTPUT)
        self.pins.digital_write(trigger, False)
        self.pins.digital_write(trigger, True)
        self.pins.digital_write(trigger, False)
        self.pins.pin_mode(echo, PinMode.INPUT)
        microseconds = self._echoes.get((trigger, echo), 0)
        if microseconds > self.ULTRASOUND_TIMEOUT_US:
            return 0
        return microseconds

    @abstractmethod
    def _reading_mm(self, microseconds: int) -> int:
        """The distance this firmware reports, in mm, for an echo of ``microseconds``."""

    def _boot(self) -> bytes:
        self.pins.reset()
        return self._boot_sketch()

    @abstractmethod
    def _boot_sketch(self) -> bytes:
        """Run the sketch's ``setup()``; return what it prints."""
