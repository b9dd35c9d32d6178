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
        self._unpower_when_safe = False
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

    @property
    def unpower_when_safe(self) -> bool:
        """Whether :meth:`make_safe` switches every servo off (``False`` unless set).

        By default the servos are left where they are, the safest choice for most
        mechanisms; sr-robot3 and sbot switch them off when the program ends, and their
        APIs on j5aio (:mod:`j5aio.compat`) set this to do the same.
        """
        return self._unpower_when_safe

    @unpower_when_safe.setter
    def unpower_when_safe(self, value: bool) -> None:
        if not isinstance(value, bool):
            raise TypeError(f"unpower_when_safe must be True or False, not {value!r}")
        self._unpower_when_safe = value

    async def make_safe(self) -> None:
        """Leave the servos where they are, or switch them off if :attr:`unpower_when_safe`."""
        if self._unpower_when_safe:
            for servo in self._servos:
                await servo.set_position(None)
