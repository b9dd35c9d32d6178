"""The Student Robotics v4 Servo Board with the serial firmware (4.3, the SR 2023+ kit)."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.sr.v4.servo_board import ServoBoard
from j5aio.components.flag import Flag
from j5aio.components.pulse_servo import PulseServo
from j5aio.components.supply_sensor import SupplySensor

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.servo import Servo

__all__ = ["ServoBoardFw4"]


class ServoBoardFw4(ServoBoard):
    """The Student Robotics v4 Servo Board running the serial firmware 4.3: twelve servos.

    Everything a :class:`~j5aio.boards.sr.v4.servo_board.ServoBoard` does works the same, so
    programs written for the older firmware keep working. On top of that:

    * each servo is a :class:`~j5aio.components.pulse_servo.PulseServo`: its positions
      -1 to 1 map onto pulse limits (1000 to 2000 µs unless changed), and it reads back
      the pulse the board really gives, in 5 µs steps;
    * ``None`` unpowers a servo;
    * :attr:`supply` measures the servo rail, :attr:`power_good` and
      :attr:`watchdog_failed` report the board's status flags.

    The SourceBots fork of the firmware, with eight servos, is
    :class:`~j5aio.boards.sb.servo_board.SBServoBoard`, a subclass with another
    :attr:`~j5aio.boards.sr.v4.servo_board.ServoBoard.SERVO_COUNT`. It is a class of its own
    (not a per-board channel count) so that a board group, the sync facade and
    autocompletion all know how many servos there are.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "Student Robotics v4 Servo Board (firmware 4.3)"

    #: The identifier of the "power good" flag.
    POWER_GOOD: ClassVar[int] = 0
    #: The identifier of the "watchdog failed" flag.
    WATCHDOG_FAILED: ClassVar[int] = 1

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._supply = SupplySensor(0, backend)
        self._power_good = Flag(self.POWER_GOOD, backend)
        self._watchdog_failed = Flag(self.WATCHDOG_FAILED, backend)

    def _make_servo(self, identifier: int, backend: Backend) -> Servo:
        return PulseServo(identifier, backend)

    @property
    def servos(self) -> tuple[PulseServo, ...]:
        """The servos, numbered from 0."""
        return cast(tuple[PulseServo, ...], self._servos)

    @property
    def supply(self) -> SupplySensor:
        """The servo rail's voltage and current."""
        return self._supply

    @property
    def power_good(self) -> Flag:
        """Raised while the servo rail's regulator reports good power."""
        return self._power_good

    @property
    def watchdog_failed(self) -> Flag:
        """Raised when the board lost touch with its pulse generator (often: no 12 V)."""
        return self._watchdog_failed

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on this Servo Board."""
        return {PulseServo, SupplySensor, Flag}
