"""The Student Robotics v4 Power Board running firmware 4.4 (the SR 2023+ kit's board).

It is a :class:`~j5aio.boards.sr.v4.power_board.PowerBoard` with more to it: a seventh
output (the 5 V rail), outputs that report an over-current trip, run and error LEDs
that can flash by themselves, and a thermometer, a fan and a 5 V regulator voltmeter.
Output L2 powers the brain: it can be read but not switched, and the output group
leaves it alone when it switches every output.
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Mapping
from enum import Enum
from types import MappingProxyType
from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.sr.v4.power_board import PowerBoard, PowerOutputPosition
from j5aio.components._checks import check_timeout
from j5aio.components.battery_sensor import BatterySensor
from j5aio.components.button import Button
from j5aio.components.component import Interface
from j5aio.components.fan import Fan, FanInterface
from j5aio.components.flashing_led import FlashingLED, FlashingLEDInterface, LEDMode
from j5aio.components.led import LED
from j5aio.components.piezo import Piezo
from j5aio.components.power_output import PowerOutput, PowerOutputGroup
from j5aio.components.protected_power_output import (
    ProtectedPowerOutput,
    ProtectedPowerOutputInterface,
)
from j5aio.components.temperature_sensor import TemperatureSensor, TemperatureSensorInterface
from j5aio.components.voltage_sensor import VoltageSensor, VoltageSensorInterface

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = [
    "BoardResetInterface",
    "PowerBoardFw4",
    "PowerBoardOutput",
    "PowerBoardOutputGroup",
]


class PowerBoardOutput(Enum):
    """The outputs of the firmware 4 power board, by the name printed beside them.

    The values are the output numbers on the wire. ``L2`` powers the brain.
    """

    H0 = 0
    H1 = 1
    L0 = 2
    L1 = 3
    L2 = 4
    L3 = 5
    FIVE_VOLT = 6


class BoardResetInterface(Interface):
    """The coroutine a backend implements to put a whole board in its own safe state."""

    @abstractmethod
    async def reset_board(self) -> None:
        """Reset the board to its safe state (for the power board, ``*RESET``)."""
        raise NotImplementedError


class PowerBoardOutputGroup(PowerOutputGroup[PowerOutputPosition]):
    """The outputs of a firmware 4 power board.

    Look an output up by :class:`PowerBoardOutput`, by the seed kit's
    :class:`~j5aio.boards.sr.v4.power_board.PowerOutputPosition`, or by number.
    :meth:`power_on` and :meth:`power_off` switch every output but L2, the brain's.

    :param outputs: the outputs, each under its name.
    """

    __slots__ = ("_switchable",)

    def __init__(self, outputs: Mapping[PowerBoardOutput, PowerOutput]) -> None:
        # Keyed by PowerBoardOutput; lookups by PowerOutputPosition go by number.
        super().__init__(cast(Mapping[PowerOutputPosition, PowerOutput], outputs))
        self._switchable = PowerOutputGroup(
            {key: output for key, output in outputs.items() if key is not PowerBoardOutput.L2},
        )

    def __getitem__(self, key: PowerBoardOutput | PowerOutputPosition | int) -> PowerOutput:
        """Return the output under ``key`` (a name of either kind, or a number).

        :raises KeyError: there is no output under ``key``.
        """
        number: int = key.value if isinstance(key, PowerBoardOutput | PowerOutputPosition) else key
        return super().__getitem__(number)

    async def power_on(self) -> None:
        """Switch on every output but L2 (the brain's, which is always on)."""
        await self._switchable.power_on()

    async def power_off(self) -> None:
        """Switch off every output but L2 (the brain's, which cannot be switched)."""
        await self._switchable.power_off()


class PowerBoardFw4(PowerBoard):
    """The Student Robotics v4 Power Board with firmware 4.4 (the SR 2023+ kit).

    Everything a :class:`~j5aio.boards.sr.v4.power_board.PowerBoard` has, and: output 6
    (the 5 V rail); outputs that tell whether their over-current trip has switched them
    off (``get_is_overcurrent``); LEDs that flash on their own
    (``await board.run_led.set_mode(LEDMode.FLASH)``); the board's temperature, fan and
    5 V regulator voltage. Switching L2, the brain's output, raises
    :class:`~j5aio.errors.NotSupportedByHardwareError` before anything is sent.

    The start button is latched by the board: it reads as pressed if it was pressed
    at any time since the previous read (the internal or the external button). A note
    on the piezo replaces the note playing: the board keeps no queue.

    :meth:`make_safe` resets the board (``*RESET``): every output off but the brain's,
    LEDs dark, the buzzer silent, over-current trips cleared.

    :param serial_number: the board's asset tag.
    :param backend: the backend that drives the board.
    :raises TypeError: the backend cannot reset the board.
    """

    name: ClassVar[str] = "Student Robotics v4 Power Board (firmware 4)"

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        if not isinstance(backend, BoardResetInterface):
            raise TypeError(
                f"{type(backend).__name__} cannot drive a {self.name}: it does not "
                "implement BoardResetInterface (reset_board)",
            )
        self._reset_backend = backend
        protected = cast(ProtectedPowerOutputInterface, backend)
        outputs: dict[PowerBoardOutput, PowerOutput] = {
            position: ProtectedPowerOutput(position.value, protected)
            for position in PowerBoardOutput
        }
        self._fw4_outputs = PowerBoardOutputGroup(MappingProxyType(outputs))
        leds = cast(FlashingLEDInterface, backend)
        self._run_led = FlashingLED(0, leds)
        self._error_led = FlashingLED(1, leds)
        self._temperature_sensor = TemperatureSensor(
            0, cast(TemperatureSensorInterface, backend),
        )
        self._fan = Fan(0, cast(FanInterface, backend))
        self._regulator_sensor = VoltageSensor(0, cast(VoltageSensorInterface, backend))

    @property
    def outputs(self) -> PowerBoardOutputGroup:
        """The seven outputs, by :class:`PowerBoardOutput`, ``PowerOutputPosition`` or number."""
        return self._fw4_outputs

    @property
    def run_led(self) -> FlashingLED:
        """The run LED (LED 0), which can flash by itself."""
        return cast(FlashingLED, self._run_led)

    @property
    def error_led(self) -> FlashingLED:
        """The error LED (LED 1), which can flash by itself."""
        return cast(FlashingLED, self._error_led)

    @property
    def temperature_sensor(self) -> TemperatureSensor:
        """The board's thermometer."""
        return self._temperature_sensor

    @property
    def fan(self) -> Fan:
        """The board's fan, which runs above 40 °C."""
        return self._fan

    @property
    def regulator_sensor(self) -> VoltageSensor:
        """The voltmeter on the 5 V regulator's output."""
        return self._regulator_sensor

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a firmware 4 Power Board."""
        return {
            PowerOutput, ProtectedPowerOutput, Piezo, Button, BatterySensor, LED, FlashingLED,
            TemperatureSensor, Fan, VoltageSensor,
        }

    async def make_safe(self) -> None:
        """Reset the board: every output off but the brain's, LEDs dark, buzzer silent."""
        await self._reset_backend.reset_board()

    async def wait_for_start_flash(self, timeout: float | None = None) -> None:
        """Flash the run LED (the board flashes it) until start is pressed, then light it.

        A press before the wait began does not count: the board's button latch is read
        once and forgotten first.

        :param timeout: give up after this many seconds; ``None`` waits for ever.
        :raises TimeoutError: the button was not pressed within ``timeout`` seconds.
        :raises TypeError: ``timeout`` is not a number or ``None``.
        :raises ValueError: ``timeout`` is negative or not a number (NaN).
        """
        check_timeout(timeout)  # bad input: nothing is sent
        await self.run_led.set_mode(LEDMode.FLASH)
        # The wait forgets a press latched before it (as the backend's first read).
        await self._start_button.wait_until_pressed(timeout)
        await self.run_led.set_mode(LEDMode.ON)
