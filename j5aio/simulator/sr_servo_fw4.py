r"""Simulators of the SR Servo Board v4 with the serial text firmware.

The protocol is described in :doc:`/internals/sr-servo-board`.

Two firmwares share the protocol:

- :class:`SRServoBoardFw4Simulator`: Student Robotics firmware 4.3, 12 servos, pulses of
  500 to 4000 µs;
- :class:`SBServoBoardFw4Simulator`: the SourceBots fork, firmware 4.4, 8 servos, pulses
  of 300 to 4000 µs.

Transport: a USB CDC port (``1BDA:0011``, "Student Robotics" / "Servo Board v4"; the baud
rate is ignored). Bytes are collected into a line until ``\n``; the line is cut at its
first ``\r``; 63 bytes without a newline are thrown away. The replies to every line in one
received packet share a 64-byte buffer, so a packet of many commands gets its replies
concatenated and cut at 64 bytes. Each reply is one ``\n``-terminated line.

======================= ============================================================
command                 reply
======================= ============================================================
``*IDN?``               ``Student Robotics:SBv4B:<asset>:<version>``
``*STATUS?``            ``<watchdog failed 0/1>:<power good 0/1>``
``*RESET``              ``ACK``; every servo disabled
``SERVO:<n>:SET:<µs>``  ``ACK``; enables servo n at ``µs`` rounded down to 5 µs ticks
``SERVO:<n>:GET?``      the pulse in µs (a multiple of 5), ``0`` when disabled
``SERVO:<n>:DISABLE``   ``ACK``; no more pulses on servo n
``SERVO:I?``            the servo rail's current, mA
``SERVO:V?``            the servo rail's voltage, mV
``*DBG:SERVOS:<phase>`` the pulses of that phase's servos (phases 1-3)
``ECHO:<text>``         ``<text>`` (the first ``:``-separated field)
======================= ============================================================

Power: the microcontroller is powered from USB and always answers, but the pulse
expander and the servo rail hang off the board's 12 V input (a power board output).
While :attr:`~SRServoBoardFw4Simulator.powered` is false, ``*STATUS?`` reports the
watchdog failed and power not good, the rail reads 0 V and no servo gets pulses
(setpoints are still taken, and pulses start when power comes).

Errors are ``NACK:<reason>`` with the firmware's texts. The board has no USB disconnect
handler: servos keep pulsing when the host goes away; plugging it in again (a USB-powered
boot) starts with every servo disabled.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import ClassVar, Final

from .base import SerialBoardSimulator
from .loads import SERVO_BOARD_IDLE_CURRENT, SERVO_HOLDING_CURRENT
from .sr_text_line import LINE_LIMIT, BoundedLineInput, answer_lines

__all__ = ["SBServoBoardFw4Simulator", "SRServoBoardFw4Simulator"]

_TICK_US: Final = 5
_MAX_PULSE_US: Final = 4000
_PHASES: Final = 3


def _leading_number(text: bytes) -> int | None:
    """Read the digits at the start of ``text`` as the firmware does; None if it has none."""
    end = 0
    while end < len(text) and text[end : end + 1].isdigit():
        end += 1
    return int(text[:end]) if end else None


class SRServoBoardFw4Simulator(SerialBoardSimulator):
    """An SR Servo Board v4 running Student Robotics firmware 4.3 (12 servos).

    :param serial_number: the asset tag: the USB serial number and the ``*IDN?`` field.
    """

    baudrate: ClassVar[int] = 115_200
    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = True

    #: The version ``*IDN?`` reports.
    VERSION: ClassVar[str] = "4.3"
    #: The number of servo channels.
    SERVO_COUNT: ClassVar[int] = 12
    #: The shortest pulse accepted, in µs.
    MIN_PULSE_US: ClassVar[int] = 500

    def __init__(self, serial_number: str) -> None:
        super().__init__(
            serial_number,
            usb_vid=0x1BDA,
            usb_pid=0x0011,
            manufacturer="Student Robotics",
            product="Servo Board v4",
        )
        self._input = BoundedLineInput(LINE_LIMIT)
        self._ticks: list[int | None] = [None] * self.SERVO_COUNT
        #: The servo rail's current, in mA.
        self.current_ma = 0
        #: The servo rail's voltage, in mV.
        self.voltage_mv = 5500
        #: Whether the regulator reports good power.
        self.power_good = True
        #: Whether the I²C link to the pulse expander has timed out.
        self.watchdog_failed = False
        self._powered = True
        self._commands: dict[bytes, Callable[[list[bytes]], bytes]] = {
            b"*IDN?": self._identify,
            b"*STATUS?": self._status,
            b"*RESET": self._reset_servos,
            b"SERVO": self._servo,
            b"*DBG": self._debug,
            b"ECHO": self._echo,
        }
        self._boot()

    # --- inspection and outside control ---

    @property
    def identity(self) -> str:
        """The ``*IDN?`` reply, without its newline."""
        return f"Student Robotics:SBv4B:{self.serial_number}:{self.VERSION}"

    @property
    def pulse_widths(self) -> tuple[int | None, ...]:
        """Each servo's pulse in µs (whole ticks), ``None`` for a servo getting no pulses.

        That is a disabled servo, or every servo while the board has no 12 V.
        """
        if not self._powered:
            return (None,) * self.SERVO_COUNT
        return tuple(None if ticks is None else ticks * _TICK_US for ticks in self._ticks)

    @property
    def powered(self) -> bool:
        """Whether the board's 12 V input is on (it starts on: a kit's wiring switches it)."""
        return self._powered

    @powered.setter
    def powered(self, on: bool) -> None:
        if on != self._powered:
            self._powered = on
            self._tell_listeners()

    def supply_current(self) -> float:
        """The amps the board draws from its 12 V input now (see :mod:`.loads`)."""
        if not self._powered:
            return 0.0
        pulsing = sum(ticks is not None for ticks in self._ticks)  # (pulse_widths's)
        return SERVO_BOARD_IDLE_CURRENT + pulsing * SERVO_HOLDING_CURRENT

    def set_supply(self, *, voltage: float | None = None, current: float | None = None) -> None:
        """Set what the servo rail's meters read, in volts and amps."""
        if voltage is not None:
            self.voltage_mv = round(voltage * 1000)
        if current is not None:
            self.current_ma = round(current * 1000)

    # --- firmware ---

    def _boot(self) -> bytes:
        self._input.reset()
        self._ticks = [None] * self.SERVO_COUNT
        return b""

    def _process(self, data: bytes) -> bytes:
        return answer_lines(self._input, data, self._run)

    def _run(self, line: bytes) -> bytes:
        fields = line.split(b":")
        handler = self._commands.get(fields[0])
        if handler is None:
            return b"NACK:Unknown command: '" + fields[0] + b"'"
        return handler(fields[1:])

    def _identify(self, _arguments: list[bytes]) -> bytes:
        return self.identity.encode("ascii")

    def _status(self, _arguments: list[bytes]) -> bytes:
        watchdog_failed = self.watchdog_failed or not self._powered
        return b"%d:%d" % (watchdog_failed, self.power_good and self._powered)

    def _reset_servos(self, _arguments: list[bytes]) -> bytes:
        self._ticks = [None] * self.SERVO_COUNT
        return b"ACK"

    def _echo(self, arguments: list[bytes]) -> bytes:
        return arguments[0] if arguments else b""

    def _servo(self, arguments: list[bytes]) -> bytes:
        if not arguments or not arguments[0]:
            return b"NACK:Missing servo number"
        if arguments[0] == b"I?":
            return str(self.current_ma if self._powered else 0).encode("ascii")
        if arguments[0] == b"V?":
            return str(self.voltage_mv if self._powered else 0).encode("ascii")
        servo = _leading_number(arguments[0])
        if servo is None or servo >= self.SERVO_COUNT:
            return b"NACK:Invalid servo number"
        if len(arguments) < 2 or not arguments[1]:
            return b"NACK:Missing servo command"
        command = arguments[1]
        if command == b"SET":
            return self._set(servo, arguments[2:])
        if command == b"GET?":
            ticks = self._ticks[servo]
            return b"0" if ticks is None else str(ticks * _TICK_US).encode("ascii")
        if command == b"DISABLE":
            self._ticks[servo] = None
            return b"ACK"
        return b"NACK:Unknown servo command"

    def _set(self, servo: int, arguments: list[bytes]) -> bytes:
        if not arguments or not arguments[0]:
            return b"NACK:Missing servo setpoint"
        pulse = _leading_number(arguments[0])
        if pulse is None or not self.MIN_PULSE_US <= pulse <= _MAX_PULSE_US:
            return b"NACK:Invalid servo setpoint"
        self._ticks[servo] = pulse // _TICK_US
        return b"ACK"

    def _debug(self, arguments: list[bytes]) -> bytes:
        if not arguments or not arguments[0]:
            return b"NACK:Missing debug command"
        if arguments[0] != b"SERVOS":
            return b"NACK:Unknown debug command"
        if len(arguments) < 2 or not arguments[1]:
            return b"NACK:Missing phase number"
        phase = _leading_number(arguments[1])
        if phase is None or not 1 <= phase <= _PHASES:
            return b"NACK:Invalid phase number"
        # Servos are staggered over three phases; list this phase's pulses (0: off).
        widths = self.pulse_widths[phase - 1 :: _PHASES]
        return b",".join(str(width or 0).encode("ascii") for width in widths)


class SBServoBoardFw4Simulator(SRServoBoardFw4Simulator):
    """A servo board running the SourceBots fork, firmware 4.4 (8 servos, from 300 µs)."""

    VERSION: ClassVar[str] = "4.4"
    SERVO_COUNT: ClassVar[int] = 8
    MIN_PULSE_US: ClassVar[int] = 300
