"""The console backend of the Student Robotics v4 Power Board with firmware 4.4."""

from __future__ import annotations

from datetime import timedelta
from typing import ClassVar

from j5aio.backends.console.console import Console
from j5aio.backends.console.sr.v4.power_board import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4.power_board_fw4 import (
    BoardResetInterface,
    PowerBoardFw4,
    PowerBoardOutput,
)
from j5aio.components.fan import FanInterface
from j5aio.components.flashing_led import FlashingLEDInterface, LEDMode
from j5aio.components.protected_power_output import ProtectedPowerOutputInterface
from j5aio.components.temperature_sensor import TemperatureSensorInterface
from j5aio.components.voltage_sensor import VoltageSensorInterface
from j5aio.errors import NotSupportedByHardwareError

__all__ = ["SRV4PowerBoardFw4ConsoleBackend"]


class SRV4PowerBoardFw4ConsoleBackend(
    ProtectedPowerOutputInterface,
    FlashingLEDInterface,
    TemperatureSensorInterface,
    FanInterface,
    VoltageSensorInterface,
    BoardResetInterface,
    SRV4PowerBoardConsoleBackend,
):
    """The firmware 4 Power Board on the console.

    As :class:`~j5aio.backends.console.sr.v4.power_board.SRV4PowerBoardConsoleBackend`,
    with seven outputs (L2, the brain's, starts on and cannot be switched), LEDs that
    can flash, and the status readings (over-current trips, temperature, fan, 5 V
    regulator voltage) asked for.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = PowerBoardFw4

    #: The longest note the board can play, in milliseconds.
    MAX_BUZZ_MS: ClassVar[int] = 2**31 - 1
    #: The buzzer's frequency range, in hertz.
    FREQUENCY_RANGE: ClassVar[tuple[int, int]] = (8, 10_000)

    _OUTPUTS: ClassVar[range] = range(len(PowerBoardOutput))
    _BRAIN: ClassVar[int] = PowerBoardOutput.L2.value

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._output_states[self._BRAIN] = True
        self._led_modes = [LEDMode.OFF for _ in self._LEDS]

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Print that an output is switched on or off.

        :raises NotSupportedByHardwareError: output 4 (L2) powers the brain.
        """
        self._check_identifier("power output", identifier, self._OUTPUTS)
        if identifier == self._BRAIN:
            raise NotSupportedByHardwareError(
                "output L2 (4) powers the robot's brain: the power board does not let it be "
                "switched. Use another output for your devices.",
            )
        await super().set_power_output_enabled(identifier, enabled)

    async def get_power_output_overcurrent(self, identifier: int) -> bool:
        """Ask whether an output has tripped on over-current."""
        self._check_identifier("power output", identifier, self._OUTPUTS)
        return await self._console.read(
            f"Has power output {identifier} tripped on over-current [true/false]", bool,
        )

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Print the note the buzzer plays now (it replaces any note playing).

        :raises NotSupportedByHardwareError: outside 8 to 10000 Hz, or under 1 ms.
        """
        low, high = self.FREQUENCY_RANGE
        if not low <= round(pitch) <= high:
            self._check_identifier("piezo", identifier, range(1))
            raise NotSupportedByHardwareError(
                f"the power board's buzzer plays {low} to {high} Hz, not {pitch} Hz",
            )
        if round(duration / timedelta(milliseconds=1)) < 1:
            self._check_identifier("piezo", identifier, range(1))
            raise NotSupportedByHardwareError(
                f"the power board plays notes of at least 1 ms, not {duration}",
            )
        await super().buzz(identifier, duration, pitch)

    async def get_led_mode(self, identifier: int) -> LEDMode:
        """Return what LED ``identifier`` (0: run, 1: error) was last set to."""
        self._check_identifier("LED", identifier, self._LEDS)
        return self._led_modes[identifier]

    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        """Print that LED ``identifier`` (0: run, 1: error) is off, on or flashing."""
        self._check_identifier("LED", identifier, self._LEDS)
        await self._console.info(f"Set LED {identifier} to {mode.name}")
        self._led_modes[identifier] = mode

    async def get_led_state(self, identifier: int) -> bool:
        """Return whether LED ``identifier`` was last lit or set flashing."""
        return await self.get_led_mode(identifier) is not LEDMode.OFF

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Print that LED ``identifier`` is lit or dark."""
        await self.set_led_mode(identifier, LEDMode.ON if state else LEDMode.OFF)

    async def get_temperature(self, identifier: int) -> float:
        """Ask for the board's temperature, in °C."""
        self._check_identifier("temperature sensor", identifier, range(1))
        return await self._console.read("Board temperature [°C]", float)

    async def get_fan_running(self, identifier: int) -> bool:
        """Ask whether the fan runs."""
        self._check_identifier("fan", identifier, range(1))
        return await self._console.read("Is the fan running [true/false]", bool)

    async def get_voltage_sensor_voltage(self, identifier: int) -> float:
        """Ask for the 5 V regulator's voltage, in volts."""
        self._check_identifier("voltage sensor", identifier, range(1))
        return await self._console.read("5V regulator voltage [volts]", float)

    async def reset_board(self) -> None:
        """Print that the board resets: outputs off but the brain's, LEDs off, silence."""
        await self._console.info("Resetting the board: outputs off (but L2), LEDs off")
        self._output_states = [index == self._BRAIN for index in self._OUTPUTS]
        self._led_modes = [LEDMode.OFF for _ in self._LEDS]
