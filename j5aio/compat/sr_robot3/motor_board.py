"""sr-robot3's motor board on j5aio's: powers in [-1, 1], ``BRAKE`` and ``COAST``."""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING

from j5aio.compat._shared import status
from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.compat.sr_robot3.utils import BoardIdentity, float_bounds_check, map_to_int
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import CommunicationError
from j5aio.sync import MonitoredMotor, MotorBoardFw4
from j5aio.sync.wrapping import call, unwrap

if TYPE_CHECKING:
    from j5aio.sync import Motor as CoreMotor
    from j5aio.sync import MotorBoard as CoreMotorBoard

__all__ = ["Motor", "MotorBoard", "MotorPower", "MotorStatus"]

_COAST = MotorSpecialState.COAST
_POWER_ERROR = "Motor power is a float between -1.0 and 1.0"


class MotorPower(IntEnum):
    """The special powers: ``BRAKE`` (0, the terminals shorted) and ``COAST`` (driver off)."""

    BRAKE = 0
    COAST = -1024  # (outside the range of powers)


class MotorStatus(status.MotorBoardStatus):
    """The motor board's status: a fault flag per motor, and its input voltage (V)."""

    __slots__ = ()


class Motor:
    """One motor.

    :param motor: j5aio's motor.
    :param index: its number on the board.
    """

    __slots__ = ("_get_power", "_index", "_motor", "_set_power")

    def __init__(self, motor: CoreMotor, index: int) -> None:
        self._motor = motor
        self._index = index
        # The core's coroutines, called through the sync facade's runtime (one call each,
        # as j5aio.sync's own property makes).
        core = unwrap(motor)
        self._get_power = core.get_power
        self._set_power = core.set_power

    @property
    def power(self) -> float:
        """The motor's power in [-1, 1], or ``COAST`` when its driver is off (``BRAKE`` is 0).

        Set it to a number in [-1, 1] (sent in thousandths, truncated), ``BRAKE`` or
        ``COAST``.

        :raises TypeError: the power set is not a number.
        :raises ValueError: the power set is outside [-1, 1].
        """
        try:
            state: float | MotorSpecialState = call(self._get_power)
        except CommunicationError as error:
            raise disconnected(error) from error
        if state is _COAST:
            return MotorPower.COAST
        if isinstance(state, MotorSpecialState):
            return 0.0  # (BRAKE: the board reports power 0)
        return round(state, 3)

    @power.setter
    def power(self, value: float) -> None:
        if value == MotorPower.COAST:
            target: float | MotorSpecialState = _COAST
        else:
            checked = float_bounds_check(value, -1.0, 1.0, _POWER_ERROR)
            # sr-robot3's thousandths, truncated; j5aio sends round(p x 1000) of this.
            target = map_to_int(checked, -1.0, 1.0, -1000, 1000) / 1000
        try:
            call(self._set_power, target)
        except CommunicationError as error:
            raise disconnected(error) from error

    @property
    def current(self) -> float:
        """The motor's current draw, in amps."""
        if not isinstance(self._motor, MonitoredMotor):
            return 0.0  # (a firmware 3 board has no current sense)
        try:
            return self._motor.current
        except CommunicationError as error:
            raise disconnected(error) from error

    @property
    def in_fault(self) -> bool:
        """Whether the motor's driver reports a fault."""
        if not isinstance(self._motor, MonitoredMotor):
            return False
        try:
            return self._motor.has_fault
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__} index={self._index} {self._motor!r}>"


class MotorBoard:
    """A motor board, as sr-robot3 shows it.

    :param board: j5aio's motor board.
    """

    __slots__ = ("_board", "_motors")

    def __init__(self, board: CoreMotorBoard) -> None:
        self._board = board
        first, second = (Motor(motor, index) for index, motor in enumerate(board.motors))
        self._motors = (first, second)

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``MCv4B``."""
        return "MCv4B"

    @property
    def motors(self) -> tuple[Motor, Motor]:
        """The board's two motors."""
        return self._motors

    def identify(self) -> BoardIdentity:
        """The board's identity: maker, type, asset tag and firmware version."""
        return BoardIdentity(
            "Student Robotics", self.get_board_type(), self._board.serial_number,
            self._board.firmware_version or "",
        )

    @property
    def status(self) -> MotorStatus:
        """The board's status: each motor's fault flag and the input voltage."""
        board = self._board
        try:
            voltage = (
                board.input_voltage_sensor.voltage if isinstance(board, MotorBoardFw4) else 0.0
            )
            return MotorStatus(tuple(motor.in_fault for motor in self._motors), voltage)
        except CommunicationError as error:
            raise disconnected(error) from error

    def reset(self) -> None:
        """Stop both motors: they coast (as the board's reset does)."""
        for motor in self._motors:
            motor.power = MotorPower.COAST

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._board!r}>"
