"""sr-robot3's servo board on j5aio's: positions in [-1, 1] through per-servo pulse limits."""

from __future__ import annotations

from typing import TYPE_CHECKING, Final

from j5aio.compat._shared import status
from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.compat.sr_robot3.utils import BoardIdentity, float_bounds_check
from j5aio.errors import CommunicationError, NotSupportedByHardwareError
from j5aio.sync import PulseServo, ServoBoardFw4
from j5aio.sync.wrapping import call, unwrap

if TYPE_CHECKING:
    from j5aio.sync import Servo as CoreServo
    from j5aio.sync import ServoBoard as CoreServoBoard

__all__ = ["DUTY_MAX", "DUTY_MIN", "NUM_SERVOS", "Servo", "ServoBoard", "ServoStatus"]

#: The shortest and longest pulse limits a servo may be given, in µs.
DUTY_MIN: Final = 500
DUTY_MAX: Final = 4000
#: The pulse limits every servo starts with, in µs.
START_DUTY_MIN: Final = 1000
START_DUTY_MAX: Final = 2000
#: How many servos the board drives.
NUM_SERVOS: Final = 12

_LIMITS_ERROR = f"Servo pulse limits are ints in µs, in the range {DUTY_MIN} to {DUTY_MAX}"


class ServoStatus(status.ServoBoardStatus):
    """The servo board's status: whether its watchdog fired, whether its supply is good."""

    __slots__ = ()


class Servo:
    """One servo.

    :param servo: j5aio's servo.
    :param index: its number on the board.
    """

    __slots__ = ("_duty_max", "_duty_min", "_get_position", "_index", "_servo", "_set_position")

    def __init__(self, servo: CoreServo, index: int) -> None:
        self._servo = servo
        self._index = index
        core = unwrap(servo)  # (its coroutines, called through the sync facade's runtime)
        self._get_position = core.get_position
        self._set_position = core.set_position
        self._duty_min = START_DUTY_MIN
        self._duty_max = START_DUTY_MAX

    @property
    def _reversed(self) -> bool:
        return self._duty_min > self._duty_max

    def set_duty_limits(self, lower: int, upper: int) -> None:
        """Make positions -1 and 1 give pulses of ``lower`` and ``upper`` µs.

        ``lower`` may be above ``upper``: the servo then turns the other way.

        :raises TypeError: a limit is not an int.
        :raises ValueError: a limit is outside 500 to 4000 µs, or the two are equal.
        """
        if not (isinstance(lower, int) and isinstance(upper, int)):
            raise TypeError(_LIMITS_ERROR)
        if not (DUTY_MIN <= lower <= DUTY_MAX and DUTY_MIN <= upper <= DUTY_MAX):
            raise ValueError(_LIMITS_ERROR)
        if lower == upper:
            raise ValueError(
                f"Servo pulse limits must differ (got {lower} µs for both): a servo whose "
                "every position is one pulse cannot be moved"
            )
        if isinstance(self._servo, PulseServo):
            try:
                self._servo.set_pulse_limits(min(lower, upper), max(lower, upper))
            except CommunicationError as error:
                raise disconnected(error) from error
        self._duty_min = lower
        self._duty_max = upper

    def get_duty_limits(self) -> tuple[int, int]:
        """The pulses of positions -1 and 1, in µs."""
        return self._duty_min, self._duty_max

    @property
    def position(self) -> float | None:
        """The servo's position in [-1, 1], or ``None`` when it is off.

        Set it to a number in [-1, 1], or ``None`` to switch the servo off.

        :raises TypeError: the position set is not a number.
        :raises ValueError: the position set is outside [-1, 1].
        """
        try:
            position: float | None = call(self._get_position)
        except CommunicationError as error:
            raise disconnected(error) from error
        if position is None:
            return None
        return -position + 0.0 if self._reversed else position

    @position.setter
    def position(self, value: float | None) -> None:
        if value is None:
            self.disable()
            return
        checked = float_bounds_check(
            value, -1.0, 1.0, "Servo position is a float between -1.0 and 1.0")
        try:
            # Reversed limits are j5aio's limits in order with the position turned round:
            # the pulse is the same.
            call(self._set_position, -checked if self._reversed else checked)
        except CommunicationError as error:
            raise disconnected(error) from error

    def disable(self) -> None:
        """Switch the servo off (no pulses).

        :raises OSError: the board cannot switch a servo off (a firmware 2 board).
        """
        try:
            self._servo.position = None
        except NotSupportedByHardwareError as error:
            raise OSError(str(error)) from error
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__} index={self._index} {self._servo!r}>"


class ServoBoard:
    """A servo board, as sr-robot3 shows it.

    :param board: j5aio's servo board.
    """

    __slots__ = ("_board", "_servos")

    def __init__(self, board: CoreServoBoard) -> None:
        self._board = board
        self._servos = tuple(Servo(servo, index) for index, servo in enumerate(board.servos))

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``SBv4B``."""
        return "SBv4B"

    @property
    def servos(self) -> tuple[Servo, ...]:
        """The board's servos."""
        return self._servos

    def identify(self) -> BoardIdentity:
        """The board's identity: maker, type, asset tag and firmware version."""
        return BoardIdentity(
            "Student Robotics", self.get_board_type(), self._board.serial_number,
            self._board.firmware_version or "",
        )

    def _fw4(self) -> ServoBoardFw4:
        board = self._board
        if not isinstance(board, ServoBoardFw4):
            raise disconnected(CommunicationError(
                f"{board.name} does not report its supply or status (it needs firmware 4)"))
        return board

    def status(self) -> ServoStatus:
        """The board's status: whether its watchdog fired, whether its supply is good."""
        board = self._fw4()
        try:
            return ServoStatus(board.watchdog_failed.state, board.power_good.state)
        except CommunicationError as error:
            raise disconnected(error) from error

    def reset(self) -> None:
        """Switch every servo off (as the board's reset does)."""
        for servo in self._servos:
            servo.disable()

    @property
    def current(self) -> float:
        """The current drawn by the servos on the main supply, in amps."""
        board = self._fw4()
        try:
            return board.supply.current
        except CommunicationError as error:
            raise disconnected(error) from error

    @property
    def voltage(self) -> float:
        """The voltage of the board's regulator, in volts."""
        board = self._fw4()
        try:
            return board.supply.voltage
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._board!r}>"
