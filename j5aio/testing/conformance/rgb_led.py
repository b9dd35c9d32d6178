"""The conformance suite of :class:`~j5aio.components.rgb_led.RGBLEDInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.rgb_led import RGBChannel, RGBLEDInterface

from ._base import InterfaceConformance, Subject

__all__ = ["RGBLEDInterfaceConformance", "RGBLEDSubject"]


@dataclass(kw_only=True)
class RGBLEDSubject(Subject):
    """A backend implementing :class:`.RGBLEDInterface`, for :class:`RGBLEDInterfaceConformance`.

    :param observe: returns the duty cycle ``channel`` of RGB LED ``identifier`` really
        shows (read from a simulator, say).
    """

    backend: RGBLEDInterface
    observe: Callable[[int, RGBChannel], Awaitable[float]] | None = None


class RGBLEDInterfaceConformance(InterfaceConformance[RGBLEDSubject]):
    """What every implementation of :class:`~j5aio.components.rgb_led.RGBLEDInterface` must do.

    * the duty cycle last set on a channel is read back (within
      :attr:`duty_cycle_tolerance`; boards with on/off LEDs set a tolerance of 0.5 and
      :attr:`duty_cycles` to 0 and 1), for every channel of every LED;
    * setting one channel leaves the other channels, and the other LEDs, as they were;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a duty cycle read back may be from the one set.
    duty_cycle_tolerance: ClassVar[float] = 0.01

    #: The duty cycles the round-trip test sets, in order.
    duty_cycles: ClassVar[tuple[float, ...]] = (1.0, 0.5, 0.25, 0.0)

    async def _check(
        self, subject: RGBLEDSubject, identifier: int, channel: RGBChannel, duty: float,
    ) -> None:
        got = await subject.backend.get_rgb_led_channel_duty_cycle(identifier, channel)
        assert math.isclose(got, duty, abs_tol=self.duty_cycle_tolerance), (
            f"{channel.name} of RGB LED {identifier} was set to {duty} but reads {got}"
        )
        if subject.observe is not None:
            seen = await subject.observe(identifier, channel)
            assert math.isclose(seen, duty, abs_tol=self.duty_cycle_tolerance), (
                f"{channel.name} of RGB LED {identifier} was set to {duty}, the board shows {seen}"
            )

    async def test_set_then_get_round_trips(self, subject: RGBLEDSubject) -> None:
        """Each duty cycle set on each channel is read back."""
        identifier = subject.identifiers[0]
        with self.bounded():
            for channel in RGBChannel:
                for duty in self.duty_cycles:
                    await subject.backend.set_rgb_led_channel_duty_cycle(
                        identifier, channel, duty,
                    )
                    await self._check(subject, identifier, channel, duty)

    async def test_every_identifier(self, subject: RGBLEDSubject) -> None:
        """Each channel of each LED can be lit alone; every other channel stays dark."""
        lit = max(self.duty_cycles)
        dark = min(self.duty_cycles)
        backend = subject.backend
        with self.bounded():
            for identifier in subject.identifiers:
                for channel in RGBChannel:
                    await backend.set_rgb_led_channel_duty_cycle(identifier, channel, dark)
            for identifier in subject.identifiers:
                for channel in RGBChannel:
                    await backend.set_rgb_led_channel_duty_cycle(identifier, channel, lit)
                    for other in subject.identifiers:
                        for other_channel in RGBChannel:
                            alone = (other, other_channel) == (identifier, channel)
                            await self._check(
                                subject, other, other_channel, lit if alone else dark,
                            )
                    await backend.set_rgb_led_channel_duty_cycle(identifier, channel, dark)

    async def test_out_of_range_identifier_raises(self, subject: RGBLEDSubject) -> None:
        """An RGB LED the board does not have is refused, for reading and for writing."""
        backend = subject.backend
        await self.assert_refused(
            subject,
            lambda i: backend.get_rgb_led_channel_duty_cycle(i, RGBChannel.RED),
            "get_rgb_led_channel_duty_cycle",
        )
        await self.assert_refused(
            subject,
            lambda i: backend.set_rgb_led_channel_duty_cycle(i, RGBChannel.RED, 1.0),
            "set_rgb_led_channel_duty_cycle",
        )
