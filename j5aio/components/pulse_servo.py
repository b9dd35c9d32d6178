"""Pulse servos: servos whose positions map onto pulse widths between per-servo limits."""

from __future__ import annotations

import math
from abc import abstractmethod
from typing import Final, cast

from j5aio.components._checks import describe
from j5aio.components.servo import Servo, ServoInterface

__all__ = [
    "DEFAULT_PULSE_LIMITS",
    "PulseLimits",
    "PulseServo",
    "PulseServoInterface",
    "position_for_pulse",
    "pulse_for_position",
]

PulseLimits = tuple[int, int]
"""Pulse widths in whole µs: (the pulse at position -1, the pulse at position 1)."""

#: The pulse limits a servo starts with, in µs: position -1 is 1000 µs, 1 is 2000 µs.
DEFAULT_PULSE_LIMITS: Final[PulseLimits] = (1000, 2000)


def pulse_for_position(position: float, limits: PulseLimits) -> int:
    """Return the pulse in µs for ``position`` in [-1, 1] between ``limits`` (low, high).

    ``int((position + 1) x (high - low) / 2 + low)``, as sr-robot3 and sbot compute it.

    :raises ValueError: ``position`` is outside [-1, 1] or NaN.
    """
    if not -1 <= position <= 1:
        raise ValueError(f"a servo position must be between -1 and 1, not {position}")
    low, high = limits
    return int((position + 1) * (high - low) / 2 + low)


def position_for_pulse(pulse_us: int, limits: PulseLimits) -> float:
    """Return the position in [-1, 1] of a pulse, between ``limits`` (low, high).

    ``(pulse - low) x 2 / (high - low) - 1``, rounded to 3 places as sr-robot3 does, and
    kept within [-1, 1]: a pulse set under wider limits reads as the nearer end.
    """
    low, high = limits
    position = round((pulse_us - low) * 2 / (high - low) - 1, 3)
    return math.copysign(1.0, position) if abs(position) > 1 else position + 0.0


class PulseServoInterface(ServoInterface):
    """The coroutines a backend implements to drive servos through pulse limits."""

    @abstractmethod
    async def get_servo_pulse_range(self, identifier: int) -> PulseLimits:
        """Return the shortest and longest pulse, in µs, the board can give servo ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def get_servo_pulse_limits(self, identifier: int) -> PulseLimits:
        """Return the pulses, in µs, that positions -1 and 1 of servo ``identifier`` map to."""
        raise NotImplementedError

    @abstractmethod
    async def set_servo_pulse_limits(self, identifier: int, limits: PulseLimits) -> None:
        """Map positions -1 and 1 of servo ``identifier`` to ``limits`` (already validated)."""
        raise NotImplementedError

    @abstractmethod
    async def get_servo_pulse_width(self, identifier: int) -> int | None:
        """Return the pulse the board gives servo ``identifier``, in µs (``None``: unpowered)."""
        raise NotImplementedError


class PulseServo(Servo):
    """A servo driven by pulses whose widths are set by its position.

    Position -1 gives the lower pulse limit and 1 the upper one (the board's defaults,
    such as 1000 and 2000 µs, unless changed with :meth:`set_pulse_limits`); positions in
    between are spread evenly.

    :param identifier: the number of the servo on its board.
    :param backend: the backend that drives the servo.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[PulseServoInterface]:
        """The interface a backend implements for pulse servos: :class:`PulseServoInterface`."""
        return PulseServoInterface

    @property
    def _pulses(self) -> PulseServoInterface:
        return cast(PulseServoInterface, self._backend)

    async def get_pulse_range(self) -> PulseLimits:
        """Return the shortest and longest pulse the board can give this servo, in µs."""
        return await self._pulses.get_servo_pulse_range(self._identifier)

    async def get_pulse_limits(self) -> PulseLimits:
        """Return the pulses that positions -1 and 1 give, in µs."""
        return await self._pulses.get_servo_pulse_limits(self._identifier)

    async def set_pulse_limits(self, lower: int, upper: int) -> None:
        """Make positions -1 and 1 give pulses of ``lower`` and ``upper`` µs.

        :param lower: the pulse at position -1, in whole µs.
        :param upper: the pulse at position 1, in whole µs, more than ``lower``.
        :raises TypeError: a limit is not an int (a bool is refused too).
        :raises ValueError: ``lower`` is not below ``upper``, or a limit is outside the
            range the board's firmware accepts (see :meth:`get_pulse_range`).
        """
        for name, value in (("lower", lower), ("upper", upper)):
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError(
                    f"the {name} pulse limit must be a whole number of µs; got {describe(value)}",
                )
        if lower >= upper:
            raise ValueError(
                f"the lower pulse limit must be below the upper one; got {lower} and {upper} µs",
            )
        shortest, longest = await self.get_pulse_range()
        if lower < shortest or upper > longest:
            raise ValueError(
                f"pulse limits must be within {shortest} to {longest} µs on this board's "
                f"firmware; got {lower} to {upper} µs",
            )
        await self._pulses.set_servo_pulse_limits(self._identifier, (lower, upper))

    async def get_pulse_width(self) -> int | None:
        """Return the pulse the board gives this servo, in µs, or ``None`` when unpowered.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._pulses.get_servo_pulse_width(self._identifier)
