"""The conformance suite of :class:`~j5aio.components.flashing_led.FlashingLEDInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

import anyio

from j5aio.components.flashing_led import FlashingLEDInterface

from .led import LEDInterfaceConformance, LEDSubject

__all__ = ["FlashingLEDInterfaceConformance", "FlashingLEDSubject"]


@dataclass(kw_only=True)
class FlashingLEDSubject(LEDSubject):
    """A backend implementing :class:`FlashingLEDInterface`.

    :param observe_changes: returns how many times LED ``identifier`` has changed
        between lit and dark so far (from a simulator, say).
    """

    backend: FlashingLEDInterface
    observe_changes: Callable[[int], Awaitable[int]] | None = None


class FlashingLEDInterfaceConformance(LEDInterfaceConformance):
    """What every implementation of :class:`FlashingLEDInterface` must do.

    Everything :class:`~.led.LEDInterfaceConformance` checks, and:

    * an LED told to flash says it is flashing, and (when observed) really changes;
    * setting its state stops the flashing;
    * an identifier the board does not have is refused.
    """

    async def test_flash_then_set(self, subject: FlashingLEDSubject) -> None:
        """Flashing is reported (and seen) until the state is set."""
        backend = subject.backend
        with self.bounded():
            for identifier in subject.identifiers:
                before = (
                    await subject.observe_changes(identifier) if subject.observe_changes else 0
                )
                await backend.set_led_flashing(identifier, 0.04)
                assert await backend.get_led_flashing(identifier) is True, (
                    f"LED {identifier} was told to flash but does not say it is flashing"
                )
                if subject.observe_changes is not None:
                    # The LED is flashed by the board (or a thread): poll what it shows.
                    while await subject.observe_changes(identifier) < before + 2:  # noqa: ASYNC110
                        await anyio.sleep(0.01)
                await backend.set_led_state(identifier, False)
                assert await backend.get_led_flashing(identifier) is False, (
                    f"LED {identifier} still flashes after its state was set"
                )
                assert await backend.get_led_state(identifier) is False, (
                    f"LED {identifier} was set off after flashing but reads lit"
                )

    async def test_out_of_range_identifier_raises_for_flashing(
        self, subject: FlashingLEDSubject,
    ) -> None:
        """An LED the board does not have is refused by the flashing methods too."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_led_flashing, "get_led_flashing")
        await self.assert_refused(
            subject, lambda i: backend.set_led_flashing(i, 1.0), "set_led_flashing",
        )
