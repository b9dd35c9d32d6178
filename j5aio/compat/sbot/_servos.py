"""sbot's ``servos``: every servo of every servo board, numbered across the boards."""

from __future__ import annotations

from collections import defaultdict
from typing import TYPE_CHECKING

from j5aio.compat._shared import status

from ._checks import float_bounds_check, map_to_float, map_to_int
from ._errors import translate_errors
from ._kit import KitLink

if TYPE_CHECKING:
    from j5aio.sync import PulseServo

__all__ = [
    "DUTY_MAX",
    "DUTY_MIN",
    "NUM_SERVOS",
    "START_DUTY_MAX",
    "START_DUTY_MIN",
    "Servo",
    "ServoStatus",
]

#: The shortest pulse limit sbot accepts, in µs.
DUTY_MIN = 300
#: The longest pulse limit sbot accepts, in µs.
DUTY_MAX = 4000
#: The pulse at position -1 until changed, in µs.
START_DUTY_MIN = 350
#: The pulse at position 1 until changed, in µs.
START_DUTY_MAX = 1980
#: Servos on one board.
NUM_SERVOS = 8


class ServoStatus(status.ServoBoardStatus):
    """The servo board's status flags."""

    __slots__ = ()

    # sbot's class has this classmethod itself, so its API surface lists it here.
    from_status_response = vars(status.ServoBoardStatus)["from_status_response"]


@translate_errors
class Servo:
    """Every servo of the robot, by number: 0 to 7 on the first servo board, 8 to 15 next.

    A position from -1.0 to 1.0 maps onto pulse limits (350 to 1980 µs until
    :meth:`set_duty_limits` changes them), with sbot's arithmetic, so the board gets the
    same pulse as under sbot.

    :param boards: the kit the servos are found on.
    """

    __slots__ = ("_applied", "_boards", "_duty_limits")

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards
        self._duty_limits: defaultdict[int, tuple[int, int]] = defaultdict(
            lambda: (START_DUTY_MIN, START_DUTY_MAX),
        )
        # The pulse limits last given to each j5aio servo (by sbot's number).
        self._applied: dict[int, tuple[int, int]] = {}

    def set_duty_limits(self, id: int, lower: int, upper: int) -> None:
        """Set the pulses, in µs, that positions -1 and 1 of servo ``id`` give.

        ``lower`` may be above ``upper``, which reverses the servo.

        :raises TypeError: a limit is not an int.
        :raises ValueError: a limit is outside 300 to 4000 µs, or there is no servo ``id``.
        """
        self._boards.servo(id)
        message = f"Servo pulse limits are ints in μs, in the range {DUTY_MIN} to {DUTY_MAX}"
        if not (isinstance(lower, int) and isinstance(upper, int)):
            raise TypeError(message)
        if not (DUTY_MIN <= lower <= DUTY_MAX and DUTY_MIN <= upper <= DUTY_MAX):
            raise ValueError(message)
        self._duty_limits[id] = (lower, upper)

    def get_duty_limits(self, id: int) -> tuple[int, int]:
        """Return the pulses, in µs, that positions -1 and 1 of servo ``id`` give."""
        self._boards.servo(id)
        return self._duty_limits[id]

    def set_position(self, id: int, position: float) -> None:
        """Move servo ``id`` to ``position`` (-1.0 to 1.0), powering it if it was off.

        :raises TypeError: ``position`` is not a number.
        :raises ValueError: ``position`` is outside [-1, 1], or there is no servo ``id``.
        """
        output = self._boards.servo(id)
        checked = float_bounds_check(
            position, -1.0, 1.0, "Servo position is a float between -1.0 and 1.0",
        )
        duty_min, duty_max = self._duty_limits[id]
        pulse = map_to_int(checked, -1.0, 1.0, duty_min, duty_max)
        limits, target = _j5aio_limits(output.component, pulse, (duty_min, duty_max), checked)
        if self._applied.get(id) != limits:
            output.component.set_pulse_limits(*limits)
            self._applied[id] = limits
        output.component.position = target

    def get_position(self, id: int) -> float | None:
        """Return servo ``id``'s position as its pulse reads back, or ``None`` when off.

        Not limited to [-1, 1]: a pulse set under other limits reads as it maps.
        """
        output = self._boards.servo(id)
        pulse = output.component.pulse_width
        if pulse is None:
            return None
        duty_min, duty_max = self._duty_limits[id]
        return map_to_float(pulse, duty_min, duty_max, -1.0, 1.0, precision=3)

    def disable(self, id: int) -> None:
        """Stop the pulses to servo ``id``, so that it goes limp."""
        self._boards.servo(id).component.position = None

    def status(self, id: int) -> ServoStatus:
        """Return the status flags of the board servo ``id`` is on."""
        board = self._boards.servo(id).board
        return ServoStatus(
            watchdog_failed=board.watchdog_failed.state, power_good=board.power_good.state,
        )

    def reset(self) -> None:
        """Stop the pulses to every servo of every board (what a board's reset does)."""
        self._boards.robot  # noqa: B018 - the boards must be loaded
        for output in self._boards.servos:
            output.component.position = None

    def get_current(self, id: int) -> float:
        """Return the current of the servo rail of servo ``id``'s board, in amps."""
        return self._boards.servo(id).board.supply.current

    def get_voltage(self, id: int) -> float:
        """Return the voltage of the servo rail of servo ``id``'s board, in volts."""
        return self._boards.servo(id).board.supply.voltage

    def __repr__(self) -> str:
        serials = ", ".join(board.serial_number for board in self._boards.servo_boards)
        return f"<{self.__class__.__qualname__} {serials}>"


def _j5aio_limits(
    servo: PulseServo, pulse: int, limits: tuple[int, int], position: float,
) -> tuple[tuple[int, int], float]:
    """Return the limits and position that make j5aio's ``servo`` give ``pulse`` µs.

    ``pulse`` is what sbot works out from ``position`` and ``limits``. With rising
    limits j5aio's servo is given the same limits and position: it works the pulse out
    with the same formula, so it is the same number. Limits that fall (a reversed servo)
    or are equal are not limits j5aio accepts: the servo is then given its board's whole
    range and the position that lands on ``pulse``.
    """
    low, high = limits
    if low < high:
        return limits, position
    low, high = servo.pulse_range
    if pulse >= high:
        return (low, high), 1.0
    # Half a µs up, so that j5aio's truncation lands on the pulse.
    return (low, high), (pulse + 0.5 - low) * 2 / (high - low) - 1
