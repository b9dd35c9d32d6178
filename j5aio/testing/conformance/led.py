"""The conformance suite of :class:`~j5aio.components.led.LEDInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from j5aio.components.led import LEDInterface

from ._base import InterfaceConformance, Subject

__all__ = ["LEDInterfaceConformance", "LEDSubject"]


@dataclass(kw_only=True)
class LEDSubject(Subject):
    """A backend implementing :class:`.LEDInterface`, for :class:`LEDInterfaceConformance`.

    :param observe: returns whether LED ``identifier`` is really lit (read from a
        simulator, say), so the suite can check the board, not just the backend's word.
    """

    backend: LEDInterface
    observe: Callable[[int], Awaitable[bool]] | None = None


class LEDInterfaceConformance(InterfaceConformance[LEDSubject]):
    """What every implementation of :class:`~j5aio.components.led.LEDInterface` must do.

    * the state last set is the state read back, for every LED;
    * setting one LED leaves the others as they were;
    * an identifier the board does not have is refused, sending nothing.
    """

    async def _check(self, subject: LEDSubject, identifier: int, state: bool) -> None:
        await self.assert_read_back(
            f"LED {identifier} was set to {state}", identifier,
            subject.backend.get_led_state, subject.observe, lambda value: value is state,
        )

    async def test_set_then_get_round_trips(self, subject: LEDSubject) -> None:
        """Lighting and darkening an LED is read back, also when repeated."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for state in (True, True, False, False, True, False):
                await subject.backend.set_led_state(identifier, state)
                await self._check(subject, identifier, state)

    async def test_every_identifier(self, subject: LEDSubject) -> None:
        """Each LED can be lit alone; its siblings stay dark."""
        with self.bounded():
            for identifier in subject.identifiers:
                await subject.backend.set_led_state(identifier, False)
            for identifier in subject.identifiers:
                await subject.backend.set_led_state(identifier, True)
                for other in subject.identifiers:
                    await self._check(subject, other, other == identifier)
                await subject.backend.set_led_state(identifier, False)

    async def test_out_of_range_identifier_raises(self, subject: LEDSubject) -> None:
        """An LED the board does not have is refused, for reading and for writing."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_led_state)
        await self.assert_refused(
            subject, lambda i: backend.set_led_state(i, True), "set_led_state",
        )
        await self.assert_refused(
            subject, lambda i: backend.set_led_state(i, False), "set_led_state",
        )
