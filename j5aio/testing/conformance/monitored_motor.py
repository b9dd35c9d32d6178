"""The conformance suite of :class:`~j5aio.components.monitored_motor.MonitoredMotorInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.monitored_motor import MonitoredMotorInterface

from ._base import require
from .motor import MotorInterfaceConformance, MotorSubject

__all__ = ["MonitoredMotorInterfaceConformance", "MonitoredMotorSubject"]


@dataclass(kw_only=True)
class MonitoredMotorSubject(MotorSubject):
    """A backend implementing :class:`~j5aio.components.monitored_motor.MonitoredMotorInterface`.

    :param set_current: makes motor ``identifier`` draw ``amps`` (a simulator's load, or
        the answer to a console prompt).
    :param set_fault: makes the driver of motor ``identifier`` report a fault, or not.
    """

    backend: MonitoredMotorInterface
    set_current: Callable[[int, float], Awaitable[None]] | None = None
    set_fault: Callable[[int, bool], Awaitable[None]] | None = None


class MonitoredMotorInterfaceConformance(MotorInterfaceConformance):
    """What every implementation of :class:`.MonitoredMotorInterface` must do.

    Everything :class:`~.motor.MotorInterfaceConformance` checks, and:

    * the current read on a driven motor is a float that follows its load;
    * the fault flag is a bool that follows the driver, motor by motor;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a current read may be from the current drawn, in amps.
    current_tolerance: ClassVar[float] = 0.01

    async def test_current_follows_the_load(self, subject: MonitoredMotorSubject) -> None:
        """The current read on each driven motor is the current it draws."""
        set_current = require(subject.set_current, "set_current")
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_motor_state(identifier, 0.5)
                for amps in (0.0, 1.5, 6.25):
                    await set_current(identifier, amps)
                    got = await subject.backend.get_motor_current(identifier)
                    assert isinstance(got, float), f"current read as {got!r}, not a float"
                    assert math.isclose(got, amps, abs_tol=self.current_tolerance), (
                        f"motor {identifier} draws {amps} A but reads {got} A"
                    )

    async def test_fault_follows_the_driver(self, subject: MonitoredMotorSubject) -> None:
        """Each driver's fault is read back on its own motor only."""
        set_fault = require(subject.set_fault, "set_fault")
        with self.bounded():
            await self.assert_each_alone(
                subject.identifiers, set_fault, subject.backend.get_motor_fault,
                lambda faulty, other, got: (
                    f"only motor {faulty} has a fault, but motor {other} reads {got!r}"
                ),
            )
            for identifier in subject.identifiers:
                assert await subject.backend.get_motor_fault(identifier) is False

    async def test_out_of_range_identifier_raises_for_readings(
        self, subject: MonitoredMotorSubject,
    ) -> None:
        """A motor the board does not have is refused by the current and fault reads."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_motor_current)
        await self.assert_refused(subject, backend.get_motor_fault)
