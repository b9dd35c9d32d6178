"""The conformance suite of :class:`~j5aio.components.motor.MotorInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from typing import ClassVar

import pytest

from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState
from j5aio.errors import NotSupportedByHardwareError

from ._base import InterfaceConformance, Subject, require

__all__ = ["MotorInterfaceConformance", "MotorSubject"]


@dataclass(kw_only=True)
class MotorSubject(Subject):
    """A backend implementing :class:`.MotorInterface`, for :class:`MotorInterfaceConformance`.

    :param observe: returns the state motor ``identifier`` is really in (read from a
        simulator, say): a power in [-1, 1] or a :class:`~j5aio.components.motor.MotorSpecialState`.
        Without it the suite only sees what the backend *reports*, which a backend that caches the
        power it was given gets right even when it sends the board the wrong number: a
        scaling or rounding bug is caught only with this hook.
    :param special_states: the special states the board has. A board without BRAKE or
        COAST declares ``special_states=()`` (or the one it has); the suite then checks
        that the missing ones are refused with
        :class:`~j5aio.errors.NotSupportedByHardwareError`, sending nothing.
    :param power_step: the smallest change of power the board can make (``1 / 125`` for a
        board driven in ±125 steps). Powers are checked to within half a step, which is
        what a rounding backend achieves and a truncating one does not; ``None`` uses the
        suite's :attr:`~MotorInterfaceConformance.power_tolerance`.
    """

    backend: MotorInterface
    observe: Callable[[int], Awaitable[MotorState]] | None = None
    special_states: Sequence[MotorSpecialState] = (MotorSpecialState.BRAKE, MotorSpecialState.COAST)
    power_step: float | None = None


def same_state(expected: MotorState, got: object, tolerance: float) -> bool:
    """Whether ``got`` is the motor state ``expected``, powers within ``tolerance``."""
    if isinstance(expected, MotorSpecialState):
        return got is expected
    if isinstance(got, bool) or not isinstance(got, int | float):
        return False
    return math.isclose(got, expected, abs_tol=tolerance)


class MotorInterfaceConformance(InterfaceConformance[MotorSubject]):
    """What every implementation of :class:`~j5aio.components.motor.MotorInterface` must do.

    * the power last set is read back, and shown by the board (with the ``observe``
      hook), to within half a power step: inexact powers such as 0.3987 and -0.4777 tell
      a rounding backend from a truncating one, on boards of 100, 125, 127, 255 and 1000
      steps each way;
    * the special states the subject declares (BRAKE and COAST by default) are read back
      as themselves; the others are refused with
      :class:`~j5aio.errors.NotSupportedByHardwareError`, sending nothing;
    * setting one motor leaves the others as they were;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a power may be from the power set, when the subject gives no power_step:
    #: half of a 1 % step (with a hair for floating point).
    power_tolerance: ClassVar[float] = 0.005 + 1e-9

    #: The powers the round-trip test sets, in order. The inexact ones fall between the
    #: steps of common boards. The last two fall between 0.6 and 0.9 of a step on a board
    #: of 100, 125, 127, 255 or 1000 steps each way (a thousandth, say, is not enough: it
    #: lands on a step of the 1000-step boards), so that a truncated power lands more
    #: than half a step from the power set, and a rounded one less than half a step.
    powers: ClassVar[tuple[float, ...]] = (
        1.0, 0.5, 0.25, 0.0, -0.25, -0.5, -1.0, 0.333, -0.333, 0.667, -0.667, 0.3987, -0.4777,
    )

    def tolerance(self, subject: MotorSubject) -> float:
        """How far a power may be from the power set, for ``subject``'s board."""
        if subject.power_step is None:
            return self.power_tolerance
        return subject.power_step / 2 + 1e-9

    async def _check(self, subject: MotorSubject, identifier: int, state: MotorState) -> None:
        tolerance = self.tolerance(subject)
        await self.assert_read_back(
            f"motor {identifier} was set to {state!r}", identifier,
            subject.backend.get_motor_state, subject.observe,
            lambda value: same_state(state, value, tolerance),
        )

    async def test_set_then_get_round_trips(self, subject: MotorSubject) -> None:
        """Each power set on a motor is read back (and shown by the board, if observed)."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for power in self.powers:
                await subject.backend.set_motor_state(identifier, power)
                await self._check(subject, identifier, power)

    async def test_the_board_shows_each_power(self, subject: MotorSubject) -> None:
        """The board itself runs each motor at the power set: scaling and rounding."""
        observe = require(subject.observe, "observe")
        with self.bounded():
            for identifier in subject.identifiers:
                for power in self.powers:
                    await subject.backend.set_motor_state(identifier, power)
                    seen = await observe(identifier)
                    assert same_state(power, seen, self.tolerance(subject)), (
                        f"motor {identifier} was set to {power!r} but the board shows "
                        f"{seen!r}: is the power scaled, and rounded rather than truncated?"
                    )

    async def test_brake_and_coast(self, subject: MotorSubject) -> None:
        """The declared special states are read back as themselves, between powers too."""
        if not subject.special_states:
            pytest.skip("the subject declares no special states (special_states=())")
        identifier = subject.identifiers[0]
        states: list[MotorState] = []
        for power in (0.5, -0.5):
            states += [*subject.special_states, power]
        with self.bounded():
            for state in states:
                await subject.backend.set_motor_state(identifier, state)
                await self._check(subject, identifier, state)

    async def test_undeclared_special_states_are_refused(self, subject: MotorSubject) -> None:
        """A special state the board lacks raises NotSupportedByHardwareError, sending nothing."""
        missing = [s for s in MotorSpecialState if s not in subject.special_states]
        if not missing:
            pytest.skip("the subject declares every special state")
        identifier = subject.identifiers[0]
        with self.bounded():
            await subject.backend.set_motor_state(identifier, 0.25)
            for state in missing:
                before = subject.sent_so_far()
                with pytest.raises(NotSupportedByHardwareError):
                    await subject.backend.set_motor_state(identifier, state)
                assert subject.sent_so_far() == before, f"refusing {state!r} sent bytes"
                await self._check(subject, identifier, 0.25)

    async def test_every_identifier(self, subject: MotorSubject) -> None:
        """Every motor can be driven on its own; its siblings keep their state."""
        baseline = -0.25  # a plain power: no BRAKE needed, and no 0.0 a board may show as BRAKE
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_motor_state(identifier, baseline)
            for identifier in subject.identifiers:
                await subject.backend.set_motor_state(identifier, 0.5)
                for other in subject.identifiers:
                    expected = 0.5 if other == identifier else baseline
                    await self._check(subject, other, expected)
                await subject.backend.set_motor_state(identifier, baseline)

    async def test_out_of_range_identifier_raises(self, subject: MotorSubject) -> None:
        """A motor the board does not have is refused, for reading and for writing."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_motor_state)
        await self.assert_refused(
            subject, lambda i: backend.set_motor_state(i, 0.5), "set_motor_state",
        )
        for state in subject.special_states:
            await self.assert_refused(
                subject,
                lambda i, state=state: backend.set_motor_state(i, state),  # type: ignore[misc]
                "set_motor_state",
            )
