r"""Simulator of the SR Motor Board v4 running firmware 4.4 / 4.5 (text protocol, 115 200 baud).

Protocol (:doc:`/internals/sr-motor-board`). The board is a UART behind an FTDI FT232R. Each
``\n``-terminated ASCII line is one command (every ``\r`` is dropped; 63 bytes without
``\n`` discard the buffer) and gets one reply line: ``ACK``, data or ``NACK:<reason>``.

``MOT:<n>:SET:<v>`` (v from -1000 to 1000) enables the driver and drives at duty
``|v| / 1000``, forwards for v > 0; v = 0 *brakes* (enabled, both half-bridges low).
``MOT:<n>:DISABLE`` *coasts* (driver off). ``MOT:<n>:GET?`` reads ``<enabled>:<value>``,
the value 0 while disabled. Both motors coast at power-up and after ``*RESET``, which
also clears the faults and the filtered currents. There is no watchdog: unplugging the
USB cable changes nothing. ``*SYS:BOOTLOADER`` answers, then the board goes silent.

Power: only the FTDI adapter is powered from USB. The controller is fed by the board's
12 V input (a power board output): while :attr:`~.sr_motor.SRMotorBoardSimulator.powered` is
false its port is there but nothing answers and no motor is driven; when power comes
the controller boots.

The firmware answers a firmware 3 resync byte (``0x00``) as part of a line, so the probe
``\x00\n*IDN?\n`` gets a NACK and then the identity.
"""

from __future__ import annotations

from typing import ClassVar, Final

from j5aio._records import FrozenRecord, frozen_record

from .loads import MOTOR_BOARD_IDLE_CURRENT, MOTOR_FULL_POWER_CURRENT
from .sr_motor import MotorDrive, SRMotorBoardSimulator
from .sr_text_line import LINE_LIMIT, BoundedLineInput

__all__ = ["MotorChannel", "MotorDrive", "SRMotorBoardFw4Simulator"]

_MOTOR_COUNT: Final = 2
_FULL_SCALE: Final = 1000
_BLUE_LED_ABOVE_MA: Final = 5000
_BOOTLOADER_REPLY: Final = b"ACK\n\n\n"


# A frozen dataclass whose ``__init__`` is written here, the rest coming from FrozenRecord
# as ``@dataclass(frozen=True)`` would make it: a simulated kit's start makes this module,
# and making the generated methods costs a few hundred microseconds. A test checks it.
@frozen_record
class MotorChannel(FrozenRecord):
    """One motor output: whether its driver is enabled, and the value last set."""

    enabled: bool = False
    value: int = 0
    """-1000 to 1000; 0 while disabled."""

    def __init__(self, enabled: bool = False, value: int = 0) -> None:
        object.__setattr__(self, "enabled", enabled)
        object.__setattr__(self, "value", value)

    @property
    def drive(self) -> MotorDrive:
        """What the driver is doing."""
        if not self.enabled:
            return MotorDrive.COAST
        if self.value == 0:
            return MotorDrive.BRAKE
        return MotorDrive.FORWARD if self.value > 0 else MotorDrive.REVERSE

    @property
    def duty(self) -> float:
        """The PWM duty, 0.0 to 1.0 (compare ``|v| x 2`` against a period of 2000)."""
        return abs(self.value) * 2 / 2000 if self.enabled else 0.0

    @property
    def power(self) -> float:
        """The signed duty: positive forwards, negative in reverse, 0 when coasting or braking."""
        return -self.duty if self.value < 0 else self.duty


class SRMotorBoardFw4Simulator(SRMotorBoardSimulator):
    """An SR Motor Board v4 with firmware 4.4 (SR) or 4.5 (SourceBots).

    :param serial_number: the FTDI serial number, which is also the asset tag.
    :param version: the firmware version ``*IDN?`` reports.
    :param input_voltage: the board's input voltage, in volts.
    """

    baudrate: ClassVar[int] = 115_200
    MOTOR_COUNT: ClassVar[int] = _MOTOR_COUNT

    def __init__(
        self,
        serial_number: str,
        *,
        version: str = "4.4.1",
        input_voltage: float = 12.0,
    ) -> None:
        super().__init__(serial_number)
        self.version = version
        self._input = BoundedLineInput(LINE_LIMIT, ignore=b"\r")
        self._motors = [MotorChannel()] * _MOTOR_COUNT
        self._faults = [False] * _MOTOR_COUNT
        self._load_ma = [0] * _MOTOR_COUNT
        self._input_mv = round(input_voltage * 1000)
        self._boot()

    # --- outside control ---

    def _stop_controller(self) -> None:
        self._input.reset()
        self._motors = [MotorChannel() if channel.value else channel for channel in self._motors]

    def supply_current(self) -> float:
        """The amps the board draws from its 12 V input now (see :mod:`.loads`).

        A motor told what it draws (:meth:`set_motor_current`) draws that while its
        driver is enabled; otherwise a driven motor draws in proportion to its duty.
        """
        if not self._powered:
            return 0.0
        total = MOTOR_BOARD_IDLE_CURRENT * 1000
        for motor, channel in enumerate(self._motors):
            if self._load_ma[motor]:
                total += self._current_ma(motor)
            else:
                total += channel.duty * MOTOR_FULL_POWER_CURRENT * 1000
        return total / 1000

    def set_motor_current(self, motor: int, amps: float) -> None:
        """Make ``motor`` draw ``amps`` while its driver is enabled.

        The board's listeners hear of it (a kit's wiring loads the output feeding it).
        """
        self._load_ma[motor] = round(amps * 1000)
        self._tell_listeners()

    def set_fault(self, motor: int, fault: bool = True) -> None:
        """Make the driver of ``motor`` report a fault (or clear it)."""
        self._faults[motor] = fault

    @property
    def input_voltage(self) -> float:
        """The board's input voltage, in volts."""
        return self._input_mv / 1000

    @input_voltage.setter
    def input_voltage(self, volts: float) -> None:
        self._input_mv = round(volts * 1000)

    # --- readable state ---

    @property
    def motors(self) -> tuple[MotorChannel, ...]:
        """The state of each motor output."""
        return tuple(self._motors)

    @property
    def faults(self) -> tuple[bool, ...]:
        """The fault flag of each driver."""
        return tuple(self._faults)

    @property
    def current_leds(self) -> tuple[bool, ...]:
        """The blue LED of each motor, lit above 5 A."""
        return tuple(self._current_ma(motor) > _BLUE_LED_ABOVE_MA for motor in range(_MOTOR_COUNT))

    def _current_ma(self, motor: int) -> int:
        return self._load_ma[motor] if self._motors[motor].enabled else 0

    # --- firmware ---

    def _boot(self) -> bytes:
        self._input.reset()
        self._motors = [MotorChannel()] * _MOTOR_COUNT
        self._faults = [False] * _MOTOR_COUNT
        self._in_bootloader = False
        return b""

    def _process(self, data: bytes) -> bytes:
        replies = bytearray()
        if not self._powered:  # the FTDI adapter takes the bytes; nobody reads them
            return b""
        for line in self._input.feed(data):
            if self._in_bootloader:
                break
            command = line.decode("ascii", errors="replace")
            if command == "*SYS:BOOTLOADER":
                self._motors = [MotorChannel()] * _MOTOR_COUNT
                self._in_bootloader = True
                replies += _BOOTLOADER_REPLY
                break
            replies += self._execute(command).encode("ascii", errors="replace") + b"\n"
        return bytes(replies)

    def _execute(self, command: str) -> str:
        fields = command.split(":")
        head, args = fields[0], fields[1:]
        if head == "*IDN?":
            return f"Student Robotics:MCv4B:{self.serial_number}:{self.version}"
        if head == "*STATUS?":
            faults = ",".join("1" if fault else "0" for fault in self._faults)
            return f"{faults}:{self._input_mv}"
        if head == "*RESET":
            self._boot()
            return "ACK"
        if head == "*SYS":
            return "NACK:Missing system command" if not args else "NACK:Invalid system command"
        if head == "MOT":
            return self._motor(args)
        if head == "ECHO":
            return args[0] if args else ""
        return f"NACK:Unknown command: '{head}'"

    def _motor(self, args: list[str]) -> str:
        if not args or not args[0]:
            return "NACK:Missing motor number"
        if args[0] not in ("0", "1"):
            return "NACK:Invalid motor number"
        motor = int(args[0])
        if len(args) < 2:
            return "NACK:Missing motor command"
        action = args[1]
        if action == "GET?":
            channel = self._motors[motor]
            return f"{int(channel.enabled)}:{channel.value}"
        if action == "I?":
            return str(self._current_ma(motor))
        if action == "DISABLE":
            self._motors[motor] = MotorChannel()
            return "ACK"
        if action != "SET":
            return "NACK:Unknown motor command"
        if len(args) < 3 or not args[2]:
            return "NACK:Missing motor power"
        value = self._parse_power(args[2])
        if value is None:
            return "NACK:Invalid motor power"
        self._motors[motor] = MotorChannel(enabled=True, value=value)
        return "ACK"

    @staticmethod
    def _parse_power(text: str) -> int | None:
        digits = text[1:] if text.startswith("-") else text
        if not digits.isdigit() or not digits.isascii():
            return None
        value = int(text)
        return value if -_FULL_SCALE <= value <= _FULL_SCALE else None
