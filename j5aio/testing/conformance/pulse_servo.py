"""The conformance suite of :class:`~j5aio.components.pulse_servo.PulseServoInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.pulse_servo import PulseServoInterface

from .servo import ServoInterfaceConformance, ServoSubject

__all__ = ["PulseServoInterfaceConformance", "PulseServoSubject"]


@dataclass(kw_only=True)
class PulseServoSubject(ServoSubject):
    """A backend implementing :class:`~j5aio.components.pulse_servo.PulseServoInterface`.

    :param observe_pulse: returns the pulse servo ``identifier`` really gets, in µs
        (``None`` when unpowered), read from a simulator, say.
    """

    backend: PulseServoInterface
    observe_pulse: Callable[[int], Awaitable[int | None]] | None = None


class PulseServoInterfaceConformance(ServoInterfaceConformance):
    """What every implementation of :class:`.PulseServoInterface` must do.

    Everything :class:`~.servo.ServoInterfaceConformance` checks, and:

    * the pulse range is two ints, shortest first, and the limits start within it;
    * limits set are read back, and positions -1, 0 and 1 give the lower limit, the
      middle and the upper limit (within :attr:`pulse_tolerance` µs), on the board too;
    * an unpowered servo has no pulse;
    * limits outside the range are refused with ``ValueError``, sending nothing and
      leaving the limits as they were;
    * an identifier the board does not have is refused by every new method.
    """

    #: How far a pulse read back may be below the pulse asked for, in µs (a tick).
    pulse_tolerance: ClassVar[int] = 5

    async def _pulse_is(self, subject: PulseServoSubject, identifier: int, pulse: int) -> None:
        got = await subject.backend.get_servo_pulse_width(identifier)
        assert got is not None and 0 <= pulse - got < max(self.pulse_tolerance, 1), (
            f"servo {identifier} should get a {pulse} µs pulse but reads {got!r}"
        )
        if subject.observe_pulse is not None:
            seen = await subject.observe_pulse(identifier)
            assert seen == got, f"servo {identifier} reads {got!r} µs, the board shows {seen!r}"

    async def test_range_and_default_limits(self, subject: PulseServoSubject) -> None:
        """The range is two ints, shortest first; the limits lie within it."""
        with self.bounded():
            for identifier in subject.identifiers:
                shortest, longest = await subject.backend.get_servo_pulse_range(identifier)
                assert isinstance(shortest, int) and isinstance(longest, int)
                assert shortest < longest
                lower, upper = await subject.backend.get_servo_pulse_limits(identifier)
                assert shortest <= lower < upper <= longest

    async def test_positions_follow_the_limits(self, subject: PulseServoSubject) -> None:
        """Positions -1, 0 and 1 give the lower limit, the middle and the upper limit."""
        identifier = subject.identifiers[0]
        backend = subject.backend
        with self.bounded():
            shortest, longest = await backend.get_servo_pulse_range(identifier)
            lower, upper = shortest, min(longest, shortest + 1000)
            await backend.set_servo_pulse_limits(identifier, (lower, upper))
            assert await backend.get_servo_pulse_limits(identifier) == (lower, upper)
            for position, pulse in ((-1.0, lower), (0.0, (lower + upper) // 2), (1.0, upper)):
                await backend.set_servo_position(identifier, position)
                await self._pulse_is(subject, identifier, pulse)
            await backend.set_servo_position(identifier, None)
            assert await backend.get_servo_pulse_width(identifier) is None

    async def test_limits_outside_the_range_are_refused(self, subject: PulseServoSubject) -> None:
        """Limits beyond the firmware's range, or not increasing, change nothing."""
        identifier = subject.identifiers[0]
        backend = subject.backend
        with self.bounded():
            shortest, longest = await backend.get_servo_pulse_range(identifier)
            before = await backend.get_servo_pulse_limits(identifier)
            sent = subject.sent_so_far()
            for limits in ((shortest - 1, longest), (shortest, longest + 1), (1600, 1400)):
                try:
                    await backend.set_servo_pulse_limits(identifier, limits)
                except ValueError:
                    pass
                else:
                    raise AssertionError(f"pulse limits {limits} were accepted")
            assert await backend.get_servo_pulse_limits(identifier) == before
            assert subject.sent_so_far() == sent, "refused pulse limits sent bytes to the board"

    async def test_out_of_range_identifier_raises_for_pulses(
        self, subject: PulseServoSubject,
    ) -> None:
        """A servo the board does not have is refused by the pulse methods too."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_servo_pulse_range)
        await self.assert_refused(subject, backend.get_servo_pulse_limits)
        await self.assert_refused(
            subject, lambda i: backend.set_servo_pulse_limits(i, (1000, 2000)),
            "set_servo_pulse_limits",
        )
        await self.assert_refused(subject, backend.get_servo_pulse_width)
