"""sbot's ``motors``: every motor of every motor board, numbered across the boards."""

from __future__ import annotations

from enum import IntEnum

from j5aio.compat._shared import status

from ._checks import float_bounds_check, map_to_float, map_to_int
from ._errors import translate_errors
from ._kit import KitLink

__all__ = ["Motor", "MotorPower", "MotorStatus"]

_FULL_SCALE = 1000


class MotorPower(IntEnum):
    """Special values for motor power."""

    BRAKE = 0
    COAST = -1024  # outside the range of powers


class MotorStatus(status.MotorBoardStatus):
    """The status of a motor board: each motor's fault flag and the input voltage."""

    __slots__ = ()

    # sbot's class has this classmethod itself, so its API surface lists it here.
    from_status_response = vars(status.MotorBoardStatus)["from_status_response"]


@translate_errors
class Motor:
    """Every motor of the robot, by number: 0 and 1 on the first motor board, 2 and 3 next.

    :param boards: the kit the motors are found on.
    """

    __slots__ = ("_boards",)

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards

    def set_power(self, id: int, power: float) -> None:
        """Drive motor ``id`` at ``power``.

        :param id: the motor's number across the boards.
        :param power: a float from -1.0 to 1.0 (sent in steps of 0.001, truncated as sbot
            does), or ``MotorPower.COAST`` / ``MotorPower.BRAKE`` (which is 0).
        :raises TypeError: ``power`` is not a number.
        :raises ValueError: ``power`` is outside [-1, 1], or there is no motor ``id``.
        """
        from j5aio.components.motor import MotorSpecialState

        output = self._boards.motor(id)
        if power == MotorPower.COAST:
            output.component.power = MotorSpecialState.COAST
            return
        checked = float_bounds_check(
            power, -1.0, 1.0, "Motor power is a float between -1.0 and 1.0",
        )
        setpoint = map_to_int(checked, -1.0, 1.0, -_FULL_SCALE, _FULL_SCALE)
        output.component.power = setpoint / _FULL_SCALE

    def get_power(self, id: int) -> float:
        """Return the power of motor ``id``: -1.0 to 1.0, or ``MotorPower.COAST``.

        A braked motor reads 0 (``MotorPower.BRAKE``).
        """
        from j5aio.components.motor import MotorSpecialState

        power = self._boards.motor(id).component.power
        if power is MotorSpecialState.COAST:
            return MotorPower.COAST
        if power is MotorSpecialState.BRAKE:
            return 0.0
        return map_to_float(round(power * _FULL_SCALE), -1000, 1000, -1.0, 1.0, precision=3)

    def status(self, id: int) -> MotorStatus:
        """Return the status of the board that motor ``id`` is on."""
        output = self._boards.motor(id)
        faults = tuple(motor.has_fault for motor in output.board.motors)
        return MotorStatus(faults, output.board.input_voltage_sensor.voltage, [])

    def reset(self) -> None:
        """Let every motor of every board coast (what a board's reset leaves them doing)."""
        from j5aio.components.motor import MotorSpecialState

        self._boards.robot  # noqa: B018 - the boards must be loaded
        for output in self._boards.motors:
            output.component.power = MotorSpecialState.COAST

    def get_motor_current(self, id: int) -> float:
        """Return the current motor ``id`` draws, in amps."""
        return self._boards.motor(id).component.current

    def in_fault(self, id: int) -> bool:
        """Return whether the driver of motor ``id`` reports a fault."""
        return self._boards.motor(id).component.has_fault

    def __repr__(self) -> str:
        serials = ", ".join(board.serial_number for board in self._boards.motor_boards)
        return f"<{self.__class__.__qualname__} {serials}>"
