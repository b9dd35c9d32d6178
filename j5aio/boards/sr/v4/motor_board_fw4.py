"""The Student Robotics v4 Motor Board running firmware 4.4 / 4.5 (the SR 2023+ kit's board)."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.components.monitored_motor import MonitoredMotor
from j5aio.components.motor import Motor, MotorSpecialState, MotorState
from j5aio.components.voltage_sensor import VoltageSensor
from j5aio.numbered import NumberedComponents

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["MotorBoardFw4"]


class MotorBoardFw4(MotorBoard):
    """The Student Robotics v4 Motor Board with firmware 4.4 or 4.5 (the SR 2023+ kit).

    Everything a :class:`~j5aio.boards.sr.v4.motor_board.MotorBoard` has; each motor
    also reports its current and whether its driver has a fault, and the board reports
    its input voltage. The power is linear in the PWM duty, in steps of 0.001.

    :param serial_number: the board's asset tag.
    :param backend: the backend that drives the board.
    :param safe_state: what :meth:`~j5aio.boards.board.Board.make_safe` sets both motors to (brake
        by default).
    """

    name: ClassVar[str] = "Student Robotics v4 Motor Board (firmware 4)"

    def __init__(
        self,
        serial_number: str,
        backend: Backend,
        *,
        safe_state: MotorState = MotorSpecialState.BRAKE,
    ) -> None:
        super().__init__(serial_number, backend, safe_state=safe_state)
        self._motors = NumberedComponents(
            (MonitoredMotor(i, backend) for i in range(self.MOTOR_COUNT)),
            owner=self,
            kind="motor",
        )
        self._input_voltage_sensor = VoltageSensor(0, backend)

    @property
    def motors(self) -> NumberedComponents[MonitoredMotor]:
        """The motors, numbered 0 and 1."""
        return cast(NumberedComponents[MonitoredMotor], self._motors)

    @property
    def input_voltage_sensor(self) -> VoltageSensor:
        """The voltmeter on the board's power input."""
        return self._input_voltage_sensor

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a firmware 4 Motor Board."""
        return {Motor, MonitoredMotor, VoltageSensor}
