"""The Bee Board on the console: prints what it would do, asks the user for the button."""

from __future__ import annotations

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.components.button import ButtonInterface
from j5aio.components.led import LEDInterface
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState
from j5aio.errors import NotSupportedByHardwareError

from .boards import BeeBoard

__all__ = ["BeeConsoleBackend"]


class BeeConsoleBackend(MotorInterface, LEDInterface, ButtonInterface, ConsoleBackend):
    """Stands in for a Bee Board with no board at all (``J5AIO_ENV=console``).

    :param serial: the board's serial number.
    :param console_class: the console to talk through (a test passes a scripted one).
    """

    board = BeeBoard

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._powers = [0.0] * BeeBoard.MOTOR_COUNT
        self._led = False

    async def get_motor_state(self, identifier: int) -> MotorState:
        """Return the power last set."""
        self._check_identifier("motor", identifier, range(BeeBoard.MOTOR_COUNT))
        return self._powers[identifier]

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Print the new power, as the board's steps would give it."""
        self._check_identifier("motor", identifier, range(BeeBoard.MOTOR_COUNT))
        if isinstance(power, MotorSpecialState):
            raise NotSupportedByHardwareError(
                f"the Bee Board's motors cannot {power.name}: set a power (0 stops a motor)",
            )
        self._powers[identifier] = round(power * 100) / 100
        await self.console.info(f"Motor {identifier} power set to {self._powers[identifier]}")

    async def get_led_state(self, identifier: int) -> bool:
        """Return the state last set."""
        self._check_identifier("LED", identifier, range(1))
        return self._led

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Print the new state."""
        self._check_identifier("LED", identifier, range(1))
        self._led = state
        await self.console.info(f"LED {'on' if state else 'off'}")

    async def get_button_state(self, identifier: int) -> bool:
        """Ask the user whether the button is held."""
        self._check_identifier("button", identifier, range(1))
        return await self.console.read("Button held [true/false]", bool)

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Wait for the user to press return, standing for the button."""
        self._check_identifier("button", identifier, range(1))
        await self.console.read("Hit return to press the button", None)
