"""The Student Robotics v4 Motor Board."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components._checks import check_number
from j5aio.components.motor import Motor, MotorSpecialState, MotorState
from j5aio.numbered import NumberedComponents

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["MotorBoard"]


class MotorBoard(Board):
    """The Student Robotics v4 Motor Board: two DC motor outputs.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    :param safe_state: what :meth:`make_safe` sets both motors to (brake by default).
    :raises TypeError: ``safe_state`` is neither a number nor a special state.
    :raises ValueError: ``safe_state`` is a number outside [-1, 1].
    """

    name: ClassVar[str] = "Student Robotics v4 Motor Board"

    #: The number of motor outputs.
    MOTOR_COUNT: ClassVar[int] = 2

    def __init__(
        self,
        serial_number: str,
        backend: Backend,
        *,
        safe_state: MotorState = MotorSpecialState.BRAKE,
    ) -> None:
        super().__init__(serial_number, backend)
        self._motors = NumberedComponents(
            (Motor(i, backend) for i in range(self.MOTOR_COUNT)), owner=self, kind="motor",
        )
        if not isinstance(safe_state, MotorSpecialState):
            safe_state = check_number(
                safe_state,
                name="safe_state",
                low=-1.0,
                high=1.0,
                allowed="MotorSpecialState.BRAKE / COAST, or a float between -1 and 1",
            )
        self._safe_state: MotorState = safe_state

    @property
    def motors(self) -> tuple[Motor, ...]:
        """The motors, numbered 0 and 1."""
        return self._motors

    @property
    def safe_state(self) -> MotorState:
        """What :meth:`make_safe` sets both motors to."""
        return self._safe_state

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a Motor Board."""
        return {Motor}

    async def make_safe(self) -> None:
        """Set both motors to the safe state given to the constructor."""
        for motor in self._motors:
            await motor.set_power(self._safe_state)
