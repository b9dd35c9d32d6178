"""The conformance suite of :class:`~j5aio.components.power_output.PowerOutputInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.power_output import PowerOutputInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["PowerOutputInterfaceConformance", "PowerOutputSubject"]


@dataclass(kw_only=True)
class PowerOutputSubject(Subject):
    """A backend implementing :class:`~j5aio.components.power_output.PowerOutputInterface`.

    :param observe: returns whether output ``identifier`` is really switched on (read
        from a simulator, say).
    :param set_current: makes output ``identifier`` draw ``amps``, so that the next
        current reading sees it. For a console backend: queue the answer to the prompt.
    """

    backend: PowerOutputInterface
    observe: Callable[[int], Awaitable[bool]] | None = None
    set_current: Callable[[int, float], Awaitable[None]] | None = None


class PowerOutputInterfaceConformance(InterfaceConformance[PowerOutputSubject]):
    """What every implementation of :class:`.PowerOutputInterface` must do.

    * the enabled state last set is read back, for every output, and switching one
      output leaves the others as they were;
    * the current read is a float, and follows the load (within
      :attr:`current_tolerance`);
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a current read may be from the current drawn, in amps.
    current_tolerance: ClassVar[float] = 0.01

    #: The currents the current test draws, in amps.
    currents: ClassVar[tuple[float, ...]] = (0.0, 0.5, 2.25, 10.0)

    async def _check(self, subject: PowerOutputSubject, identifier: int, enabled: bool) -> None:
        await self.assert_read_back(
            f"output {identifier} was set to {enabled}", identifier,
            subject.backend.get_power_output_enabled, subject.observe,
            lambda value: value is enabled,
        )

    async def test_set_then_get_round_trips(self, subject: PowerOutputSubject) -> None:
        """Switching an output on and off is read back, also when repeated."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for enabled in (True, True, False, False, True, False):
                await subject.backend.set_power_output_enabled(identifier, enabled)
                await self._check(subject, identifier, enabled)

    async def test_every_identifier(self, subject: PowerOutputSubject) -> None:
        """Every output can be switched on alone; its siblings stay off."""
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_power_output_enabled(identifier, False)
            for identifier in subject.identifiers:
                await subject.backend.set_power_output_enabled(identifier, True)
                for other in subject.identifiers:
                    await self._check(subject, other, other == identifier)
                await subject.backend.set_power_output_enabled(identifier, False)

    async def test_current_follows_the_load(self, subject: PowerOutputSubject) -> None:
        """The current read on each output is the current it draws."""
        set_current = require(subject.set_current, "set_current")
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_power_output_enabled(identifier, True)
                for amps in self.currents:
                    await set_current(identifier, amps)
                    got = await subject.backend.get_power_output_current(identifier)
                    assert isinstance(got, float), f"current read as {got!r}, not a float"
                    assert math.isclose(got, amps, abs_tol=self.current_tolerance), (
                        f"output {identifier} draws {amps} A but reads {got} A"
                    )

    async def test_out_of_range_identifier_raises(self, subject: PowerOutputSubject) -> None:
        """An output the board does not have is refused, for every call."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_power_output_enabled)
        await self.assert_refused(
            subject,
            lambda i: backend.set_power_output_enabled(i, True),
            "set_power_output_enabled",
        )
        await self.assert_refused(subject, backend.get_power_output_current)
