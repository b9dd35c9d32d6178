"""The Student Robotics v4 Servo Board."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components.servo import Servo
from j5aio.numbered import NumberedComponents

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["ServoBoard"]


class ServoBoard(Board):
    """The Student Robotics v4 Servo Board: twelve servo outputs.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "Student Robotics v4 Servo Board"

    #: The number of servo outputs.
    SERVO_COUNT: ClassVar[int] = 12

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._servos = NumberedComponents(
            (self._make_servo(i, backend) for i in range(self.SERVO_COUNT)),
            owner=self, kind="servo",
        )

    def _make_servo(self, identifier: int, backend: Backend) -> Servo:
        """Make servo ``identifier``; subclasses with richer servos override this."""
        return Servo(identifier, backend)

    @property
    def servos(self) -> tuple[Servo, ...]:
        """The servos, numbered 0 to 11."""
        return self._servos

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a Servo Board."""
        return {Servo}

    async def make_safe(self) -> None:
        """Do nothing: leaving the servos where they are is the safest choice."""
