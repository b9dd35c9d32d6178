"""The console backend of the Student Robotics v4 Power Board."""

from __future__ import annotations

from datetime import timedelta
from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sr.v4.power_board import PowerBoard, PowerOutputPosition
from j5aio.components.battery_sensor import BatterySensorInterface
from j5aio.components.button import ButtonInterface
from j5aio.components.led import LEDInterface
from j5aio.components.piezo import PiezoInterface
from j5aio.components.power_output import PowerOutputInterface
from j5aio.errors import NotSupportedByHardwareError

__all__ = ["SRV4PowerBoardConsoleBackend"]


class SRV4PowerBoardConsoleBackend(
    PowerOutputInterface,
    PiezoInterface,
    ButtonInterface,
    BatterySensorInterface,
    LEDInterface,
    ConsoleBackend,
):
    """The Power Board on the console: prints what it switches, asks for what it reads.

    Outputs, LEDs and notes are printed; currents, voltages and the start button are
    asked for.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    # j5's transcript: a flashing wait asks "Start button state" until the answer is true.
    WAITS_FOR_PRESSES: ClassVar[bool] = False

    board = PowerBoard

    #: The longest note the board can play, in milliseconds.
    MAX_BUZZ_MS: ClassVar[int] = 65535

    _OUTPUTS: ClassVar[range] = range(len(PowerOutputPosition))
    _LEDS: ClassVar[range] = range(2)

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._output_states = [False for _ in self._OUTPUTS]
        self._led_states = [False for _ in self._LEDS]

    async def get_power_output_enabled(self, identifier: int) -> bool:
        """Return whether output ``identifier`` was last switched on."""
        self._check_identifier("power output", identifier, self._OUTPUTS)
        return self._output_states[identifier]

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Print that output ``identifier`` is switched on or off."""
        self._check_identifier("power output", identifier, self._OUTPUTS)
        await self._console.info(f"Setting output {identifier} to {enabled}")
        self._output_states[identifier] = enabled

    async def get_power_output_current(self, identifier: int) -> float:
        """Ask for the current drawn from output ``identifier``, in amps."""
        self._check_identifier("power output", identifier, self._OUTPUTS)
        return await self._console.read(f"Current for power output {identifier} [amps]", float)

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Print the note the piezo would play.

        :raises NotSupportedByHardwareError: the note is longer than 65535 ms.
        """
        self._check_identifier("piezo", identifier, range(1))
        duration_ms = round(duration / timedelta(milliseconds=1))
        if duration_ms > self.MAX_BUZZ_MS:
            raise NotSupportedByHardwareError(
                f"the power board plays notes of at most {self.MAX_BUZZ_MS} ms; "
                f"{duration_ms} ms is too long",
            )
        await self._console.info(f"Buzzing at {float(pitch)}Hz for {duration_ms}ms")

    async def get_button_state(self, identifier: int) -> bool:
        """Ask whether the start button is pressed."""
        self._check_identifier("button", identifier, range(1))
        return await self._console.read("Start button state [true/false]", bool)

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Wait for the user to press return, standing for the start button."""
        self._check_identifier("button", identifier, range(1))
        await self._console.info("Waiting for start button press.")
        await self._console.read("Hit return to press start button", None)

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        """Ask for the battery voltage, in volts."""
        self._check_identifier("battery sensor", identifier, range(1))
        return await self._console.read("Battery voltage [volts]", float)

    async def get_battery_sensor_current(self, identifier: int) -> float:
        """Ask for the battery current, in amps."""
        self._check_identifier("battery sensor", identifier, range(1))
        return await self._console.read("Battery current [amps]", float)

    async def get_led_state(self, identifier: int) -> bool:
        """Return whether LED ``identifier`` (0: run, 1: error) was last lit."""
        self._check_identifier("LED", identifier, self._LEDS)
        return self._led_states[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Print that LED ``identifier`` (0: run, 1: error) is lit or dark."""
        self._check_identifier("LED", identifier, self._LEDS)
        await self._console.info(f"Set LED {identifier} to {state}")
        self._led_states[identifier] = state
