"""The conformance suite of :class:`~j5aio.components.flashing_led.FlashingLEDInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from j5aio.components.flashing_led import FlashingLEDInterface, LEDMode

from .led import LEDInterfaceConformance, LEDSubject

__all__ = ["FlashingLEDInterfaceConformance", "FlashingLEDSubject"]


@dataclass(kw_only=True)
class FlashingLEDSubject(LEDSubject):
    """A backend implementing :class:`~j5aio.components.flashing_led.FlashingLEDInterface`.

    :param observe_mode: returns the mode LED ``identifier`` is really in (read from a
        simulator, say).
    """

    backend: FlashingLEDInterface
    observe_mode: Callable[[int], Awaitable[LEDMode]] | None = None


class FlashingLEDInterfaceConformance(LEDInterfaceConformance):
    """What every implementation of :class:`.FlashingLEDInterface` must do.

    Everything :class:`~.led.LEDInterfaceConformance` checks, and:

    * the mode last set (off, on, flashing) is read back, for every LED;
    * a flashing LED reads as lit, and setting a state stops the flashing;
    * an identifier the board does not have is refused by the mode calls, sending nothing.
    """

    async def _check_mode(
        self, subject: FlashingLEDSubject, identifier: int, mode: LEDMode,
    ) -> None:
        await self.assert_read_back(
            f"LED {identifier} was set to {mode}", identifier,
            subject.backend.get_led_mode, subject.observe_mode, lambda value: value is mode,
        )

    async def test_mode_round_trips(self, subject: FlashingLEDSubject) -> None:
        """Each mode set on each LED is read back."""
        with self.bounded():
            for identifier in subject.identifiers:
                for mode in (LEDMode.FLASH, LEDMode.ON, LEDMode.OFF, LEDMode.FLASH, LEDMode.OFF):
                    await subject.backend.set_led_mode(identifier, mode)
                    await self._check_mode(subject, identifier, mode)

    async def test_state_and_mode_agree(self, subject: FlashingLEDSubject) -> None:
        """A flashing LED reads as lit; setting a state stops the flashing."""
        identifier = subject.identifiers[0]
        backend = subject.backend
        with self.bounded():
            await backend.set_led_mode(identifier, LEDMode.FLASH)
            assert await backend.get_led_state(identifier) is True
            await backend.set_led_state(identifier, False)
            await self._check_mode(subject, identifier, LEDMode.OFF)
            await backend.set_led_mode(identifier, LEDMode.FLASH)
            await backend.set_led_state(identifier, True)
            await self._check_mode(subject, identifier, LEDMode.ON)

    async def test_out_of_range_identifier_raises_for_modes(
        self, subject: FlashingLEDSubject,
    ) -> None:
        """An LED the board does not have is refused by the mode calls."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_led_mode)
        await self.assert_refused(
            subject, lambda i: backend.set_led_mode(i, LEDMode.FLASH), "set_led_mode",
        )
