"""The Student Robotics v4 Power Board."""

from __future__ import annotations

from collections.abc import Mapping
from enum import Enum
from types import MappingProxyType
from typing import TYPE_CHECKING, ClassVar

import anyio

from j5aio.boards.board import Board
from j5aio.components._checks import check_timeout
from j5aio.components.battery_sensor import BatterySensor
from j5aio.components.button import Button, ButtonInterface
from j5aio.components.led import LED
from j5aio.components.piezo import Piezo
from j5aio.components.power_output import (
    PowerOutput,
    PowerOutputGroup,
)

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["PowerBoard", "PowerOutputGroup", "PowerOutputPosition"]


class PowerOutputPosition(Enum):
    """The power outputs of the board, by the name printed beside them.

    The values are the output numbers the board uses on the wire.
    """

    H0 = 0
    H1 = 1
    L0 = 2
    L1 = 3
    L2 = 4
    L3 = 5


class PowerBoard(Board):
    """The Student Robotics v4 Power Board.

    It switches six power outputs, sounds a piezo, reads the battery and the start button,
    and lights the run LED (identifier 0) and the error LED (identifier 1).

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "Student Robotics v4 Power Board"

    #: Its outputs feed the motor and servo boards: it is made safe after them.
    MAKE_SAFE_LAST: ClassVar[bool] = True

    #: :meth:`wait_for_start_flash` switches the run LED every ``START_POLL_INTERVAL *
    #: START_FLASH_POLLS`` seconds (0.3 s). The button itself is waited for as
    #: :meth:`.Button.wait_until_pressed` does (the backend says as soon as it is
    #: pressed), or, on a backend whose every look is a question (the console), looked
    #: at every ``START_POLL_INTERVAL`` seconds, as j5 does.
    START_POLL_INTERVAL: ClassVar[float] = 0.05

    #: See :attr:`START_POLL_INTERVAL`.
    START_FLASH_POLLS: ClassVar[int] = 6

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        outputs: dict[PowerOutputPosition, PowerOutput] = {
            position: PowerOutput(position.value, backend) for position in PowerOutputPosition
        }
        self._outputs: Mapping[PowerOutputPosition, PowerOutput] = MappingProxyType(outputs)
        self._output_group = PowerOutputGroup(self._outputs)
        self._piezo = Piezo(0, backend)
        self._start_button = Button(0, backend)
        self._battery_sensor = BatterySensor(0, backend)
        self._run_led = LED(0, backend)
        self._error_led = LED(1, backend)

    @property
    def outputs(self) -> PowerOutputGroup[PowerOutputPosition]:
        """The six power outputs, by :class:`PowerOutputPosition` or by number."""
        return self._output_group

    @property
    def piezo(self) -> Piezo:
        """The piezo sounder."""
        return self._piezo

    @property
    def start_button(self) -> Button:
        """The start button."""
        return self._start_button

    @property
    def battery_sensor(self) -> BatterySensor:
        """The battery voltage and current sensor."""
        return self._battery_sensor

    @property
    def run_led(self) -> LED:
        """The run LED (LED 0), which :meth:`wait_for_start_flash` flashes."""
        return self._run_led

    @property
    def error_led(self) -> LED:
        """The error LED (LED 1)."""
        return self._error_led

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a Power Board."""
        return {PowerOutput, Piezo, Button, BatterySensor, LED}

    async def make_safe(self) -> None:
        """Switch every power output off."""
        await self._output_group.power_off()

    async def wait_for_start_flash(self, timeout: float | None = None) -> None:
        """Flash the run LED until the start button is pressed, then leave the LED on.

        The button is looked at once; then the LED changes every 0.3 s and the wait ends
        as soon as the backend sees the press (it shares its reads of the button with any
        other task waiting for it). On the console, the button is asked about every
        50 ms until it is pressed, as j5 does.
        Cancelling the wait (or running out of time) leaves the LED as it was at the time.

        :param timeout: give up after this many seconds; ``None`` waits for ever.
        :raises TimeoutError: the button was not pressed within ``timeout`` seconds.
        :raises TypeError: ``timeout`` is not a number or ``None``.
        :raises ValueError: ``timeout`` is negative or not a number (NaN).
        """
        with anyio.move_on_after(check_timeout(timeout)) as scope:
            backend = self.backend
            if not isinstance(backend, ButtonInterface) or not backend.WAITS_FOR_PRESSES:
                await self._look_until_pressed()
            # One look first, as j5 does; then the backend says when it is pressed.
            elif not await self._start_button.get_is_pressed():
                # (imported here: a program that never waits for the start loads none of it)
                from j5aio.components._first import first_of

                await first_of(
                    [self._start_button.wait_until_pressed],
                    beside=[self._flash_run_led],
                )
        if scope.cancelled_caught:
            raise TimeoutError(
                f"the start button was not pressed within {timeout} s; pass a longer "
                "timeout, or timeout=None to wait for as long as it takes",
            )
        await self._run_led.set_state(True)

    async def _look_until_pressed(self) -> None:
        """Look at the button every 50 ms, switching the LED every sixth look, as j5 does."""
        looks = 0
        led_on = False
        while not await self._start_button.get_is_pressed():
            if looks % self.START_FLASH_POLLS == 0:
                led_on = not led_on
                await self._run_led.set_state(led_on)
            await anyio.sleep(self.START_POLL_INTERVAL)
            looks += 1

    async def _flash_run_led(self) -> None:
        led_on = False
        while True:
            led_on = not led_on
            await self._run_led.set_state(led_on)
            await anyio.sleep(self.START_POLL_INTERVAL * self.START_FLASH_POLLS)
