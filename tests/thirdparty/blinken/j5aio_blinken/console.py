"""The Blinken board on the console: prints what its LEDs do."""

from __future__ import annotations

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.components.led import LEDInterface
from j5aio_blinken.board import BlinkenBoard

__all__ = ["BlinkenConsoleBackend"]


class BlinkenConsoleBackend(LEDInterface, ConsoleBackend):
    """Prints the LEDs' states instead of driving a board."""

    board = BlinkenBoard

    def __init__(self, serial: str, console_class: type | None = None) -> None:
        super().__init__(serial, console_class)
        self._states = [False] * BlinkenBoard.LED_COUNT

    async def get_led_state(self, identifier: int) -> bool:
        """Return the state last set."""
        self._check_identifier("LED", identifier, range(BlinkenBoard.LED_COUNT))
        return self._states[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Print the new state."""
        self._check_identifier("LED", identifier, range(BlinkenBoard.LED_COUNT))
        await self.console.info(f"LED {identifier} {'on' if state else 'off'}")
        self._states[identifier] = state
