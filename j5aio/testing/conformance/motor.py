"""The conformance suite of :class:`~j5aio.components.motor.MotorInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState

from ._base import InterfaceConformance, Subject

__all__ = ["MotorInterfaceConformance", "MotorSubject"]


@dataclass(kw_only=True)
class MotorSubject(Subject):
    """A backend implementing :class:`MotorInterface`, for :class:`MotorInterfaceConformance`.

    :param observe: returns the state motor ``identifier`` is really in (read from a
        simulator, say): a power in [-1, 1] or a :class:`MotorSpecialState`.
    """

    backend: MotorInterface
    observe: Callable[[int], Awaitable[MotorState]] | None = None


def same_state(expected: MotorState, got: object, tolerance: float) -> bool:
    """Whether ``got`` is the motor state ``expected``, powers within ``tolerance``."""
    if isinstance(expected, MotorSpecialState):
        return got is expected
    if isinstance(got, bool) or not isinstance(got, int | float):
        return False
    return math.isclose(got, expected, abs_tol=tolerance)


class MotorInterfaceConformance(InterfaceConformance[MotorSubject]):
    """What every implementation of :class:`MotorInterface` must do.

    * the power last set is read back (within :attr:`power_tolerance`, for boards that
      step their power), and so are BRAKE and COAST, for every motor;
    * setting one motor leaves the others as they were;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a power read back may be from the power set, for boards with power steps.
    power_tolerance: ClassVar[float] = 0.01

    #: The powers the round-trip test sets, in order.
    powers: ClassVar[tuple[float, ...]] = (1.0, 0.5, 0.25, 0.0, -0.25, -0.5, -1.0)

    async def _check(self, subject: MotorSubject, identifier: int, state: MotorState) -> None:
        got = await subject.backend.get_motor_state(identifier)
        assert same_state(state, got, self.power_tolerance), (
            f"motor {identifier} was set to {state!r} but reads back {got!r}"
        )
        if subject.observe is not None:
            seen = await subject.observe(identifier)
            assert same_state(state, seen, self.power_tolerance), (
                f"motor {identifier} was set to {state!r} but the board shows {seen!r}"
            )

    async def test_set_then_get_round_trips(self, subject: MotorSubject) -> None:
        """Each power set on a motor is read back."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for power in self.powers:
                await subject.backend.set_motor_state(identifier, power)
                await self._check(subject, identifier, power)

    async def test_brake_and_coast(self, subject: MotorSubject) -> None:
        """BRAKE and COAST are read back as themselves, between powers too."""
        identifier = subject.identifiers[0]
        states: list[MotorState] = [
            MotorSpecialState.BRAKE, 0.5, MotorSpecialState.COAST, MotorSpecialState.BRAKE,
            -0.5, MotorSpecialState.COAST,
        ]
        with self.bounded():
            for state in states:
                await subject.backend.set_motor_state(identifier, state)
                await self._check(subject, identifier, state)

    async def test_every_identifier(self, subject: MotorSubject) -> None:
        """Every motor can be driven on its own; its siblings keep their state."""
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_motor_state(identifier, MotorSpecialState.BRAKE)
            for identifier in subject.identifiers:
                await subject.backend.set_motor_state(identifier, 0.5)
                for other in subject.identifiers:
                    expected = 0.5 if other == identifier else MotorSpecialState.BRAKE
                    await self._check(subject, other, expected)
                await subject.backend.set_motor_state(identifier, MotorSpecialState.BRAKE)

    async def test_out_of_range_identifier_raises(self, subject: MotorSubject) -> None:
        """A motor the board does not have is refused, for reading and for writing."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_motor_state, "get_motor_state")
        await self.assert_refused(
            subject, lambda i: backend.set_motor_state(i, 0.5), "set_motor_state",
        )
        await self.assert_refused(
            subject,
            lambda i: backend.set_motor_state(i, MotorSpecialState.BRAKE),
            "set_motor_state",
        )
