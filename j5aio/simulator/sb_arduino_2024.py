r"""Simulator of the SourceBots Arduino with the sb2024 firmware, ``2.0``.

The protocol is described in :doc:`/internals/sb-arduino`.

Input: bytes are collected up to ``\n``; nothing else is special, so a ``\r`` stays in
the line and spoils its last field. The line is split at every ``:`` and matched
exactly; each line gets one reply line ending ``\n``. No banner at boot.

=========================================== ===============================================
line                                        reply
=========================================== ===============================================
``*IDN?``                                   ``SourceBots:Arduino:X:2.0``
``*STATUS?``                                ``Yes``
``*RESET?``                                 ``NACK:Reset not supported``
``PIN:<n>:MODE:GET?``                       ``INPUT`` / ``INPUT_PULLUP`` / ``OUTPUT``, from the
                                            direction and output registers
``PIN:<n>:MODE:SET:<mode>``                 ``ACK``; mode INPUT, INPUT_PULLUP or OUTPUT
``PIN:<n>:DIGITAL:GET?``                    ``1`` / ``0``
``PIN:<n>:DIGITAL:SET:<v>``                 ``ACK``; ``1`` drives HIGH, anything else LOW (on an
                                            input: the pull-up), whatever the mode
``PIN:<n>:ANALOG:GET?``                     ``analogRead(n)``, 0-1023 (0-5 and 14-19 are A0-A5)
``ULTRASOUND:<t>:<e>:MEASURE?``             mm = 5 x µs / 29, with µs in a signed 16-bit
                                            ``int``: an echo past 32 767 µs reads negative;
                                            0 when no echo within 60 ms
anything else                               ``NACK:Invalid command``
=========================================== ===============================================

Pin fields are read as ``String::toInt()`` does (no digits reads as 0) into a 16-bit
``int``, handed to the core functions as an 8-bit pin number: pins the Uno does not have
are ignored, read LOW, and report ``INPUT``.
"""

from __future__ import annotations

from typing import ClassVar, Final

from .arduino_base import ARDUINO_UNO_R3, ArduinoBoardSimulator, UsbIdentity
from .arduino_numbers import to_int16, to_long
from .arduino_pins import PIN_COUNT, PinMode
from .line_assembler import LineAssembler

__all__ = ["SBArduino2024Simulator"]

_IDENTITY: Final = b"SourceBots:Arduino:X:2.0"
_NACK_INVALID: Final = b"NACK:Invalid command"
_ACK: Final = b"ACK"
_FIXED_REPLIES: Final = {
    b"*IDN?": _IDENTITY,
    b"*STATUS?": b"Yes",
    b"*RESET?": b"NACK:Reset not supported",
}
_MODES: Final = {mode.value.encode(): mode for mode in PinMode}


def _pin(field: bytes) -> int:
    """A pin field as the firmware reads it: toInt() into an int, then an 8-bit pin."""
    return to_int16(to_long(field)) & 0xFF


class SBArduino2024Simulator(ArduinoBoardSimulator):
    """A SourceBots Arduino (Arduino Uno) running the sb2024 firmware."""

    ULTRASOUND_TIMEOUT_US: ClassVar[int] = 60_000
    _MM_PER_US: ClassVar[float] = 5 / 29

    def __init__(self, serial_number: str, *, usb_identity: UsbIdentity = ARDUINO_UNO_R3) -> None:
        super().__init__(serial_number, usb_identity=usb_identity)
        self._lines = LineAssembler()
        self._boot()

    @property
    def pending_input(self) -> bytes:
        """The partial line received so far."""
        return self._lines.pending

    def _boot_sketch(self) -> bytes:
        self._lines.reset()
        return b""

    def _reading_mm(self, microseconds: int) -> int:
        held = to_int16(microseconds)
        return int(5 * held / 29)  # C division truncates towards zero

    def _process(self, data: bytes) -> bytes:
        return b"".join(self._run(line) + b"\n" for line in self._lines.feed(data))

    def _run(self, line: bytes) -> bytes:
        fixed = _FIXED_REPLIES.get(line)
        if fixed is not None:
            return fixed
        fields = line.split(b":")
        if fields[0] == b"PIN" and len(fields) >= 4:
            return self._pin_command(_pin(fields[1]), fields[2:])
        if fields[0] == b"ULTRASOUND" and len(fields) == 4 and fields[3] == b"MEASURE?":
            microseconds = self._fire_ultrasound(_pin(fields[1]), _pin(fields[2]))
            return b"%d" % self._reading_mm(microseconds)
        return _NACK_INVALID

    def _pin_command(self, pin: int, rest: list[bytes]) -> bytes:
        command = rest[:2]
        if rest == [b"MODE", b"GET?"]:
            return self._mode_of(pin).value.encode()
        if command == [b"MODE", b"SET"] and len(rest) == 3 and rest[2] in _MODES:
            self.pins.pin_mode(pin, _MODES[rest[2]])
            return _ACK
        if rest == [b"DIGITAL", b"GET?"]:
            return b"1" if self.pins.digital_read(pin) else b"0"
        if command == [b"DIGITAL", b"SET"] and len(rest) == 3:
            self.pins.digital_write(pin, rest[2] == b"1")
            return _ACK
        if rest == [b"ANALOG", b"GET?"]:
            return b"%d" % self.pins.analog_read(pin)
        return _NACK_INVALID

    def _mode_of(self, pin: int) -> PinMode:
        return self.pins.mode(pin) if pin < PIN_COUNT else PinMode.INPUT
