r"""Simulator of the SR Ruggeduino single-character firmware, versions 1 and 2.

The protocol is described in :doc:`/internals/sr-arduino`.

The host sends a command letter followed by its pin letters, with no terminator; pin ``n``
is the byte ``'a' + n``. The firmware takes one command byte at a time, waits (blocking)
for each pin byte the command needs, carries it out, prints its output and then ``\n``.
Every other byte is ignored but still answered with ``\n``.

======== ====================== ======================================================
command  pins                   output
======== ====================== ======================================================
``v``                           ``SRduino:1`` (or ``SRduino:2``)
``i``    pin                    pinMode INPUT
``p``    pin                    pinMode INPUT_PULLUP
``o``    pin                    pinMode OUTPUT
``h``    pin                    digitalWrite HIGH (on an input: pull-up on)
``l``    pin                    digitalWrite LOW (on an input: pull-up off)
``r``    pin                    ``h`` or ``l``
``a``    pin                    analogRead, decimal 0-1023 (channel 0-5 or pin 14-19)
``u``    trigger, echo          version 2 only: distance in mm = 5 * µs // 29, 0 when
                                no echo within 60 ms
======== ====================== ======================================================

A pin byte is taken as ``byte - 'a'`` into an 8-bit pin number, exactly as the core
functions receive it: pins the Uno does not have are ignored and read low.
"""

from __future__ import annotations

from typing import ClassVar, Final

from .arduino_base import ARDUINO_UNO_R3, ArduinoBoardSimulator, UsbIdentity
from .arduino_pins import PinMode

__all__ = ["SRRuggeduinoSimulator"]

_PIN_BASE: Final = ord("a")
_NEWLINE: Final = b"\n"
_SINGLE_PIN_COMMANDS: Final = frozenset(b"airhlop")
_ULTRASOUND: Final = ord("u")
_VERSION: Final = ord("v")
_SUPPORTED_VERSIONS: Final = (1, 2)
_ULTRASOUND_FROM_VERSION: Final = 2


class SRRuggeduinoSimulator(ArduinoBoardSimulator):
    """An SR Ruggeduino (Arduino Uno) running the SR single-character firmware."""

    ULTRASOUND_TIMEOUT_US: ClassVar[int] = 60_000
    _MM_PER_US: ClassVar[float] = 5 / 29

    def __init__(
        self,
        serial_number: str,
        *,
        firmware_version: int = 1,
        usb_identity: UsbIdentity = ARDUINO_UNO_R3,
    ) -> None:
        if firmware_version not in _SUPPORTED_VERSIONS:
            raise ValueError(f"the SR firmware has versions 1 and 2, not {firmware_version}")
        super().__init__(serial_number, usb_identity=usb_identity)
        self._version = firmware_version
        self._command: int | None = None
        self._pins_received = bytearray()
        self._boot()

    @property
    def firmware_version(self) -> int:
        """The firmware version the board reports (1 or 2)."""
        return self._version

    @property
    def awaiting_pin(self) -> str | None:
        """The command letter whose pin byte the firmware is blocked waiting for, if any."""
        return None if self._command is None else chr(self._command)

    def _boot_sketch(self) -> bytes:
        self._command = None
        self._pins_received.clear()
        return b""

    def _reading_mm(self, microseconds: int) -> int:
        return 5 * microseconds // 29

    def _pins_needed(self, command: int) -> int:
        if command in _SINGLE_PIN_COMMANDS:
            return 1
        if command == _ULTRASOUND and self._version >= _ULTRASOUND_FROM_VERSION:
            return 2
        return 0

    def _process(self, data: bytes) -> bytes:
        emitted = bytearray()
        for byte in data:
            if self._command is None:
                if self._pins_needed(byte) == 0:
                    emitted += self._run(byte, b"")
                else:
                    self._command = byte
                continue
            self._pins_received.append(byte)
            if len(self._pins_received) == self._pins_needed(self._command):
                emitted += self._run(self._command, bytes(self._pins_received))
                self._command = None
                self._pins_received.clear()
        return bytes(emitted)

    def _run(self, command: int, pin_bytes: bytes) -> bytes:
        pins = [(byte - _PIN_BASE) & 0xFF for byte in pin_bytes]
        output = b""
        if command == _VERSION:
            output = b"SRduino:%d" % self._version
        elif command == ord("i"):
            self.pins.pin_mode(pins[0], PinMode.INPUT)
        elif command == ord("p"):
            self.pins.pin_mode(pins[0], PinMode.INPUT_PULLUP)
        elif command == ord("o"):
            self.pins.pin_mode(pins[0], PinMode.OUTPUT)
        elif command == ord("h"):
            self.pins.digital_write(pins[0], True)
        elif command == ord("l"):
            self.pins.digital_write(pins[0], False)
        elif command == ord("r"):
            output = b"h" if self.pins.digital_read(pins[0]) else b"l"
        elif command == ord("a"):
            output = b"%d" % self.pins.analog_read(pins[0])
        elif command == _ULTRASOUND and pins:
            output = self._ultrasound(pins[0], pins[1])
        return output + _NEWLINE

    def _ultrasound(self, trigger: int, echo: int) -> bytes:
        return b"%d" % self._reading_mm(self._fire_ultrasound(trigger, echo))
