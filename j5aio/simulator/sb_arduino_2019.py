r"""Simulator of the SourceBots Arduino with the 2019 line-protocol firmware.

The protocol is described in :doc:`/internals/sb-arduino`.

Two firmware versions: ``2019.6.0`` drives a PCA9685 servo shield with ``S``;
``2019.8.0`` answers every ``S`` with ``- Error: not implemented``.

Input: bytes are assembled into a line (NUL empties the partial line, CR is ignored, TAB
counts as a space, runs of spaces collapse); LF executes it. The line is trimmed and echoed
as ``# <line>\n``. A leading ``@<id> `` makes every reply line start with ``@<id> `` (an id
of 0, or one that does not parse, means no prefix). The first character is the command,
the rest its space-separated arguments, so ``W2 H`` works like ``W 2 H``.

Replies: ``> <data>`` lines, then ``+ OK`` or ``- Error: <message>`` (or
``- Error, unknown command: <c>``), each ending ``\r\n``. At boot the board prints
``# Booted\n`` and ``# SBDuino GPIO v<version>\r\n`` and sets pins 2-13 to INPUT.

======= ================ =========================================================
command arguments        reply
======= ================ =========================================================
A                        ``> a0 <n>`` ... ``> a3 <n>`` (ADC readings), ``+ OK``
L       H or L           drives pin 13 (the argument is not trimmed: ``LH``)
R       pin              ``> H`` / ``> L``
W       pin, H/L/P/Z     H, L: OUTPUT driven high/low; P: INPUT_PULLUP; Z: INPUT
T       trigger, echo    ``> <echo µs, two decimals>``
U       trigger, echo    ``> <mm>``, mm = µs * 0.1715 (single precision) truncated
S       servo, width     2019.6.0: PCA9685 channel 0-15 on for ``width`` counts
V                        ``> SBDuino GPIO v<version>``
======= ================ =========================================================
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from typing import ClassVar, Final

from .arduino_base import ARDUINO_UNO_R3, ArduinoBoardSimulator, UsbIdentity
from .arduino_numbers import WHITE_SPACE, float32, format_float, to_int16, to_long
from .arduino_pins import PinMode
from .line_assembler import LineAssembler

__all__ = ["SBArduinoFirmware", "SBArduinoSimulator"]

_LED_PIN: Final = 13
_FIRST_PIN: Final = 2
_LAST_PIN: Final = 13
_ANALOGUE_REPORTED: Final = 4  # A0-A3
_A0: Final = 14
_SERVO_COUNT: Final = 16
_SERVO_MIN: Final = 150
_SERVO_MAX: Final = 550
_PCA9685_STEPS: Final = 4096
_SERVO_FRAME_US: Final = 20_000  # 50 Hz
_MM_PER_US: Final = float32(float32(float32(float32(1e-6) * float32(343.0)) * 0.5) * 1e3)
_UINT_MAX: Final = 65535.0  # unsigned int is 16-bit on AVR


class SBArduinoFirmware(enum.Enum):
    """The 2019 firmware versions."""

    V2019_6_0 = "2019.6.0"
    """With the PCA9685 servo shield."""
    V2019_8_0 = "2019.8.0"
    """Servo support removed."""


class _CommandError(Exception):
    """A handler's ``- Error: <message>`` reply."""

    def __init__(self, message: bytes) -> None:
        super().__init__(message)
        self.message = message


def _pop_option(argument: bytes) -> tuple[bytes, bytes]:
    """The firmware's ``pop_option``: trim, then split at the first space."""
    argument = argument.strip(WHITE_SPACE)
    separator = argument.find(b" ")
    if separator == -1:
        return argument, b""
    return argument[:separator], argument[separator + 1 :]


def _two_arguments(argument: bytes, usage: bytes) -> tuple[bytes, bytes]:
    first, rest = _pop_option(argument)
    second, rest = _pop_option(rest)
    if rest or not first or not second:
        raise _CommandError(usage)
    return first, second


class SBArduinoSimulator(ArduinoBoardSimulator):
    """A SourceBots Arduino Uno running the 2019 line-protocol firmware."""

    ULTRASOUND_TIMEOUT_US: ClassVar[int] = 1_000_000
    _MM_PER_US: ClassVar[float] = _MM_PER_US
    #: Number of PCA9685 servo channels (2019.6.0).
    SERVO_COUNT: ClassVar[int] = _SERVO_COUNT

    def __init__(
        self,
        serial_number: str,
        *,
        firmware_version: SBArduinoFirmware | str = SBArduinoFirmware.V2019_6_0,
        usb_identity: UsbIdentity = ARDUINO_UNO_R3,
    ) -> None:
        super().__init__(serial_number, usb_identity=usb_identity)
        self._firmware = SBArduinoFirmware(firmware_version)
        self._lines = LineAssembler(
            clear=b"\x00", ignore=b"\r", translate={0x09: 0x20}, collapse_spaces=True
        )
        self._servo_widths = [0] * _SERVO_COUNT
        self._handlers: dict[bytes, Callable[[bytes], list[bytes]]] = {
            b"A": self._analogue,
            b"L": self._led,
            b"R": self._read_pin,
            b"S": self._servo,
            b"T": self._ultrasound_timing,
            b"U": self._ultrasound_distance,
            b"V": self._version,
            b"W": self._write_pin,
        }
        self._boot()

    # --- inspection ---

    @property
    def firmware_version(self) -> SBArduinoFirmware:
        """Which 2019 firmware the board runs."""
        return self._firmware

    @property
    def version_string(self) -> str:
        """The version text the firmware prints, e.g. ``SBDuino GPIO v2019.6.0``."""
        return f"SBDuino GPIO v{self._firmware.value}"

    @property
    def servo_widths(self) -> tuple[int, ...]:
        """The PCA9685 on-time of each servo channel in counts of 1/4096 of 20 ms (0: off)."""
        return tuple(self._servo_widths)

    def servo_pulse_us(self, servo: int) -> float:
        """The pulse width of servo channel ``servo`` in µs, assuming an exact 50 Hz frame."""
        return self._servo_widths[servo] * _SERVO_FRAME_US / _PCA9685_STEPS

    @property
    def pending_input(self) -> bytes:
        """The partial command line received so far."""
        return self._lines.pending

    # --- firmware ---

    def _boot_sketch(self) -> bytes:
        self.pins.pin_mode(_LED_PIN, PinMode.OUTPUT)
        for pin in range(_FIRST_PIN, _LAST_PIN + 1):
            self.pins.pin_mode(pin, PinMode.INPUT)
        self._servo_widths = [0] * _SERVO_COUNT
        self._lines.reset()
        return b"# Booted\n" + self._reply_line(0, b"#", self.version_string.encode())

    def _reading_mm(self, microseconds: int) -> int:
        distance = float32(float32(microseconds) * _MM_PER_US)
        return int(max(0.0, min(_UINT_MAX, distance)))

    def _process(self, data: bytes) -> bytes:
        emitted = bytearray()
        for line in self._lines.feed(data):
            emitted += self._execute(line)
        return bytes(emitted)

    @staticmethod
    def _reply_line(request_id: int, kind: bytes, text: bytes) -> bytes:
        prefix = b"@%d " % request_id if request_id else b""
        return prefix + kind + b" " + text + b"\r\n"

    def _execute(self, received: bytes) -> bytes:
        line = received.strip(WHITE_SPACE)
        echo = b"# " + line + b"\n"
        request_id = 0
        command = line
        if line.startswith(b"@"):
            separator = line.find(b" ")
            if separator == -1:
                request_id = to_int16(to_long(line[1:]))
            else:
                request_id = to_int16(to_long(line[1:separator]))
                command = line[separator + 1 :]
        return echo + self._dispatch(request_id, command)

    def _dispatch(self, request_id: int, command: bytes) -> bytes:
        letter = command[:1] or b"\x00"
        handler = self._handlers.get(letter)
        if handler is None:
            return self._reply_line(request_id, b"-", b"Error, unknown command: " + letter)
        try:
            data = handler(command[1:])
        except _CommandError as error:
            return self._reply_line(request_id, b"-", b"Error: " + error.message)
        replies = [self._reply_line(request_id, b">", item) for item in data]
        replies.append(self._reply_line(request_id, b"+", b"OK"))
        return b"".join(replies)

    # --- command handlers: each returns the ``>`` lines, or raises _CommandError ---

    def _analogue(self, argument: bytes) -> list[bytes]:
        return [
            b"a%d %d" % (channel, self.pins.analog_read(_A0 + channel))
            for channel in range(_ANALOGUE_REPORTED)
        ]

    def _led(self, argument: bytes) -> list[bytes]:
        if self._firmware is SBArduinoFirmware.V2019_8_0:
            self.pins.pin_mode(_LED_PIN, PinMode.OUTPUT)
        state = argument[:1]
        if state not in (b"H", b"L"):
            raise _CommandError(b"Unknown LED State: " + argument)
        self.pins.digital_write(_LED_PIN, state == b"H")
        return []

    @staticmethod
    def _digital_pin(text: bytes, message: bytes) -> int:
        pin = to_int16(to_long(text))
        if not _FIRST_PIN <= pin <= _LAST_PIN:
            raise _CommandError(message)
        return pin

    def _read_pin(self, argument: bytes) -> list[bytes]:
        pin_text, rest = _pop_option(argument)
        if rest or not pin_text:
            raise _CommandError(b"Bad number of arguments")
        pin = self._digital_pin(pin_text, b"pin must be between 2 and 13")
        return [b"H" if self.pins.digital_read(pin) else b"L"]

    def _write_pin(self, argument: bytes) -> list[bytes]:
        pin_text, state = _two_arguments(argument, b"Arguments Needed: <num> <state>")
        pin = self._digital_pin(pin_text, b"pin must be between 2 and 13")
        letter = state[:1]
        if letter in (b"H", b"L"):
            self.pins.pin_mode(pin, PinMode.OUTPUT)
            self.pins.digital_write(pin, letter == b"H")
        elif letter == b"P":
            self.pins.pin_mode(pin, PinMode.INPUT_PULLUP)
        elif letter == b"Z":
            self.pins.pin_mode(pin, PinMode.INPUT)
        else:
            raise _CommandError(b"Unknown pin mode")
        return []

    def _ultrasound_pins(self, argument: bytes) -> tuple[int, int]:
        trigger_text, echo_text = _two_arguments(argument, b"Arguments required: <trigger> <echo>")
        message = b"Pins must be between 2 and 13"
        trigger = to_int16(to_long(trigger_text))
        echo = to_int16(to_long(echo_text))
        if not (_FIRST_PIN <= trigger <= _LAST_PIN and _FIRST_PIN <= echo <= _LAST_PIN):
            raise _CommandError(message)
        return trigger, echo

    def _ultrasound_timing(self, argument: bytes) -> list[bytes]:
        microseconds = self._fire_ultrasound(*self._ultrasound_pins(argument))
        return [format_float(float32(microseconds))]

    def _ultrasound_distance(self, argument: bytes) -> list[bytes]:
        microseconds = self._fire_ultrasound(*self._ultrasound_pins(argument))
        return [b"%d" % self._reading_mm(microseconds)]

    def _servo(self, argument: bytes) -> list[bytes]:
        if self._firmware is SBArduinoFirmware.V2019_8_0:
            raise _CommandError(b"not implemented")
        servo_text, width_text = _two_arguments(argument, b"Arguments Required: <num> <width>")
        width = to_long(width_text)
        servo = to_long(servo_text)
        if not 0 <= servo < _SERVO_COUNT:
            raise _CommandError(b"Servo out of range")
        if width != 0 and not _SERVO_MIN <= width <= _SERVO_MAX:
            raise _CommandError(b"Width must be 0 or between 150 and 550")
        self._servo_widths[servo] = width
        return []

    def _version(self, argument: bytes) -> list[bytes]:
        return [self.version_string.encode()]
