"""The console backend of the KCH, the Raspberry Pi HAT of the SR 2023+ kit."""

from __future__ import annotations

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sr.kch import KCHBoard
from j5aio.components.flashing_led import FlashingLEDInterface, LEDMode
from j5aio.components.rgb_led import RGBChannel, RGBLEDInterface

__all__ = ["KCHConsoleBackend"]

_NAMES = ("A", "B", "C")
_COLOURS = {
    (False, False, False): "off",
    (True, False, False): "red",
    (True, True, False): "yellow",
    (False, True, False): "green",
    (False, True, True): "cyan",
    (False, False, True): "blue",
    (True, False, True): "magenta",
    (True, True, True): "white",
}


class KCHConsoleBackend(RGBLEDInterface, FlashingLEDInterface, ConsoleBackend):
    """The KCH on the console: prints each LED's colour when it changes.

    As on the real KCH, each part of a user LED is on (any brightness above 0) or off.

    :param serial: the KCH's asset code.
    :param console_class: the console to talk through.
    """

    board = KCHBoard

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._leds = [[False, False, False] for _ in _NAMES]
        self._start = False
        self._flashing = False

    async def get_rgb_led_channel_duty_cycle(self, identifier: int, channel: RGBChannel) -> float:
        """Return 1.0 if the channel is lit, else 0.0."""
        self._check_identifier("user LED", identifier, range(len(_NAMES)))
        return 1.0 if self._leds[identifier][RGBChannel(channel)] else 0.0

    async def set_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel, duty_cycle: float,
    ) -> None:
        """Light the channel for any duty cycle above 0, and print the LED's colour."""
        self._check_identifier("user LED", identifier, range(len(_NAMES)))
        self._leds[identifier][RGBChannel(channel)] = duty_cycle > 0
        red, green, blue = self._leds[identifier]
        colour = _COLOURS[(red, green, blue)]
        await self._console.info(f"User LED {_NAMES[identifier]} is now {colour}.")

    async def get_led_state(self, identifier: int) -> bool:
        """Return whether the start LED is lit (a flashing LED counts as lit)."""
        self._check_identifier("start LED", identifier, range(1))
        return self._start

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Print the start LED's new state."""
        self._check_identifier("start LED", identifier, range(1))
        self._start = state
        self._flashing = False
        await self._console.info(f"Start LED {'on' if state else 'off'}.")

    async def get_led_mode(self, identifier: int) -> LEDMode:
        """Return whether the start LED is off, on or flashing."""
        self._check_identifier("start LED", identifier, range(1))
        if self._flashing:
            return LEDMode.FLASH
        return LEDMode.ON if self._start else LEDMode.OFF

    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        """Print the start LED's new mode."""
        self._check_identifier("start LED", identifier, range(1))
        if mode is not LEDMode.FLASH:
            await self.set_led_state(identifier, mode is LEDMode.ON)
            return
        self._start = True
        self._flashing = True
        await self._console.info("Start LED flashing.")
