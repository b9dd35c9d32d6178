r"""Simulator of the SR Motor Board v4 running firmware 3 (binary protocol, 1 Mbaud).

Protocol (:doc:`/internals/sr-motor-board`). The firmware feeds each received byte to a three-state
machine:

- idle: ``0x00`` no-op (resynchronises), ``0x01`` replies ``MCV4B:3\n``, ``0x02`` / ``0x03``
  wait for a speed byte for motor 0 / 1, ``0x04`` replies ``Entering bootloader\n`` and
  resets into the STM32 ROM bootloader (silent from then on), anything else is ignored.
- waiting for a speed byte ``b`` (any byte, back to idle afterwards): 0 is ignored,
  1 coasts, 2 brakes, otherwise ``s = b - 128`` drives the motor, forwards when s >= 0,
  with a PWM compare of ``|s| * 20`` against a period of 2000, so full duty from ``|s| >= 100``.

The board does not reset when its port is opened and prints nothing at boot; the motors
start (and come back from a reset) coasting, with the driver disabled.

Power: only the USB-serial adapter is powered from USB. The controller sits on the
isolated side, fed by the board's 12 V input (a power board output): while
:attr:`~.sr_motor.SRMotorBoardSimulator.powered` is false its port is there but nothing answers
and no motor is driven; when power comes the controller boots.
"""

from __future__ import annotations

from typing import ClassVar, Final

from j5aio._records import FrozenRecord, frozen_record

from .loads import MOTOR_BOARD_IDLE_CURRENT, MOTOR_FULL_POWER_CURRENT
from .sr_motor import MotorDrive, SRMotorBoardSimulator

__all__ = ["MotorMode", "MotorOutput", "SRMotorBoardFw3Simulator"]

_CMD_VERSION: Final = 0x01
_CMD_MOTOR0: Final = 0x02
_CMD_MOTOR1: Final = 0x03
_CMD_BOOTLOADER: Final = 0x04

_SPEED_IGNORED: Final = 0
_SPEED_COAST: Final = 1
_SPEED_BRAKE: Final = 2
_SPEED_ZERO: Final = 128

_COMPARE_PER_STEP: Final = 20
_PWM_PERIOD: Final = 2000
_FULL_DUTY_STEPS: Final = _PWM_PERIOD // _COMPARE_PER_STEP

_VERSION_REPLY: Final = b"MCV4B:3\n"
_BOOTLOADER_REPLY: Final = b"Entering bootloader\n"


#: What a motor driver is doing: firmware 3's name for :class:`.sr_motor.MotorDrive`.
MotorMode = MotorDrive


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and ``__hash__``
# from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: the default kit imports
# it, and making the generated ones costs a quarter of a millisecond. A test checks them
# against those.)
@frozen_record
class MotorOutput(FrozenRecord):
    """The state of one motor output: its mode and, when driving, the speed step ``|s|``."""

    mode: MotorMode
    steps: int = 0
    """``|s|`` from the speed byte (0-127); the PWM compare value is ``steps * 20``."""

    def __init__(self, mode: MotorMode, steps: int = 0) -> None:
        object.__setattr__(self, "mode", mode)
        object.__setattr__(self, "steps", steps)

    @property
    def duty(self) -> float:
        """The PWM duty cycle 0.0-1.0 (0 unless driving; saturates at ``|s| >= 100``)."""
        if self.mode in (MotorMode.COAST, MotorMode.BRAKE):
            return 0.0
        return min(self.steps, _FULL_DUTY_STEPS) / _FULL_DUTY_STEPS

    @property
    def duty_percent(self) -> int:
        """The PWM duty cycle as a whole percentage."""
        return round(self.duty * 100)

    @property
    def power(self) -> float:
        """The signed duty: positive forwards, negative in reverse, 0 when coasting or braking."""
        return -self.duty if self.mode is MotorMode.REVERSE else self.duty


COAST: Final = MotorOutput(MotorMode.COAST)
BRAKE: Final = MotorOutput(MotorMode.BRAKE)


class SRMotorBoardFw3Simulator(SRMotorBoardSimulator):
    """An SR Motor Board v4 with firmware 3 behind its FTDI FT232R USB-serial adapter."""

    baudrate: ClassVar[int] = 1_000_000
    #: The firmware version this board reports.
    version: ClassVar[int] = 3

    def __init__(self, serial_number: str) -> None:
        super().__init__(serial_number)
        self._motors = [COAST] * self.MOTOR_COUNT
        # The motor whose speed byte the parser waits for (None: it waits for a command).
        self._awaiting: int | None = None
        self._motor_currents: list[float | None] = [None] * self.MOTOR_COUNT
        self._boot()

    def _stop_controller(self) -> None:
        self._awaiting = None
        self._motors = [
            COAST if output.mode in (MotorMode.FORWARD, MotorMode.REVERSE) else output
            for output in self._motors
        ]

    def set_motor_current(self, motor: int, amps: float | None) -> None:
        """Make ``motor`` draw ``amps`` while it is driven (``None``: the load model's figure).

        The board's listeners hear of it (a kit's wiring loads the output feeding it).
        """
        self._motor_currents[motor] = amps
        self._tell_listeners()

    def supply_current(self) -> float:
        """The amps the board draws from its 12 V input now (see :mod:`.loads`)."""
        if not self._powered:
            return 0.0
        total = MOTOR_BOARD_IDLE_CURRENT
        for output, fixed in zip(self._motors, self._motor_currents, strict=True):
            if output.mode in (MotorMode.FORWARD, MotorMode.REVERSE):
                total += fixed if fixed is not None else output.duty * MOTOR_FULL_POWER_CURRENT
        return total

    @property
    def motors(self) -> tuple[MotorOutput, ...]:
        """The state of each motor output."""
        return tuple(self._motors)

    @property
    def awaiting_speed(self) -> int | None:
        """The motor whose speed byte the parser is waiting for, or None when idle."""
        return self._awaiting

    def _boot(self) -> bytes:
        self._motors = [COAST] * self.MOTOR_COUNT
        self._awaiting = None
        self._in_bootloader = False
        return b""

    def _process(self, data: bytes) -> bytes:
        emitted = bytearray()
        if not self._powered:  # the USB-serial adapter takes the bytes; nobody reads them
            return b""
        for byte in data:
            if self._in_bootloader:
                break
            emitted += self._step(byte)
        return bytes(emitted)

    def _step(self, byte: int) -> bytes:
        motor = self._awaiting
        if motor is None:
            return self._command(byte)
        self._awaiting = None
        if byte != _SPEED_IGNORED:
            self._motors[motor] = self._decode_speed(byte)
        return b""

    def _command(self, byte: int) -> bytes:
        if byte == _CMD_VERSION:
            return _VERSION_REPLY
        if byte == _CMD_MOTOR0:
            self._awaiting = 0
        elif byte == _CMD_MOTOR1:
            self._awaiting = 1
        elif byte == _CMD_BOOTLOADER:
            # The MCU resets into ROM: the driver enables are released, the motors coast.
            self._motors = [COAST] * self.MOTOR_COUNT
            self._in_bootloader = True
            return _BOOTLOADER_REPLY
        return b""

    @staticmethod
    def _decode_speed(byte: int) -> MotorOutput:
        if byte == _SPEED_COAST:
            return COAST
        if byte == _SPEED_BRAKE:
            return BRAKE
        speed = byte - _SPEED_ZERO
        mode = MotorMode.FORWARD if speed >= 0 else MotorMode.REVERSE
        return MotorOutput(mode, abs(speed))
