"""The conformance suite of :class:`~j5aio.components.servo.ServoInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.servo import ServoInterface, ServoPosition
from j5aio.errors import NotSupportedByHardwareError

from ._base import InterfaceConformance, Subject

__all__ = ["ServoInterfaceConformance", "ServoSubject"]


@dataclass(kw_only=True)
class ServoSubject(Subject):
    """A backend implementing :class:`.ServoInterface`, for :class:`ServoInterfaceConformance`.

    :param observe: returns the position servo ``identifier`` is really driven to (read
        from a simulator, say), ``None`` when unpowered.
    """

    backend: ServoInterface
    observe: Callable[[int], Awaitable[ServoPosition]] | None = None


def same_position(expected: ServoPosition, got: object, tolerance: float) -> bool:
    """Whether ``got`` is the servo position ``expected``, within ``tolerance``."""
    if expected is None or got is None:
        return expected is got
    if isinstance(got, bool) or not isinstance(got, int | float):
        return False
    return math.isclose(got, expected, abs_tol=tolerance)


class ServoInterfaceConformance(InterfaceConformance[ServoSubject]):
    """What every implementation of :class:`~j5aio.components.servo.ServoInterface` must do.

    * the position last set is read back (within :attr:`position_tolerance`), for every
      servo;
    * ``None`` (unpowered) is read back as ``None``, or refused with
      :class:`~j5aio.errors.NotSupportedByHardwareError` by boards that cannot unpower a
      servo, leaving the servo where it was;
    * setting one servo leaves the others as they were;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a position read back may be from the position set, for boards with steps.
    position_tolerance: ClassVar[float] = 0.01

    #: The positions the round-trip test sets, in order.
    positions: ClassVar[tuple[float, ...]] = (-1.0, -0.5, 0.0, 0.25, 0.5, 1.0)

    async def _check(self, subject: ServoSubject, identifier: int, position: ServoPosition) -> None:
        await self.assert_read_back(
            f"servo {identifier} was set to {position!r}", identifier,
            subject.backend.get_servo_position, subject.observe,
            lambda value: same_position(position, value, self.position_tolerance),
        )

    async def test_set_then_get_round_trips(self, subject: ServoSubject) -> None:
        """Each position set on a servo is read back."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for position in self.positions:
                await subject.backend.set_servo_position(identifier, position)
                await self._check(subject, identifier, position)

    async def test_unpowered(self, subject: ServoSubject) -> None:
        """``None`` unpowers the servo, or is refused as unsupported, leaving it in place."""
        identifier = subject.identifiers[0]
        with self.bounded():
            await subject.backend.set_servo_position(identifier, 0.5)
            try:
                await subject.backend.set_servo_position(identifier, None)
            except NotSupportedByHardwareError:
                await self._check(subject, identifier, 0.5)
            else:
                await self._check(subject, identifier, None)
                await subject.backend.set_servo_position(identifier, -0.5)
                await self._check(subject, identifier, -0.5)

    async def test_every_identifier(self, subject: ServoSubject) -> None:
        """Every servo can be moved on its own; its siblings stay where they were."""
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_servo_position(identifier, 0.0)
            for identifier in subject.identifiers:
                await subject.backend.set_servo_position(identifier, 0.5)
                for other in subject.identifiers:
                    await self._check(subject, other, 0.5 if other == identifier else 0.0)
                await subject.backend.set_servo_position(identifier, 0.0)

    async def test_out_of_range_identifier_raises(self, subject: ServoSubject) -> None:
        """A servo the board does not have is refused, for reading and for writing."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_servo_position)
        await self.assert_refused(
            subject, lambda i: backend.set_servo_position(i, 0.5), "set_servo_position",
        )
