"""Small recording backends for the board tests, one per board.

Each records every interface call in ``calls`` as ``(method, args)`` and keeps just
enough state that a write can be read back. (A module with a unique name, not a
conftest, so test modules can import it and mypy sees one module of that name.)
"""

from __future__ import annotations

from collections.abc import Sequence
from datetime import timedelta
from typing import ClassVar

import anyio

from j5aio.backends.backend import Backend
from j5aio.boards.arduino import ArduinoUno
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard, SRArduinoBoard
from j5aio.components import (
    BatterySensorInterface,
    ButtonInterface,
    GPIOPinInterface,
    GPIOPinMode,
    LEDInterface,
    MotorInterface,
    MotorState,
    PiezoInterface,
    PowerOutputInterface,
    ServoInterface,
    ServoPosition,
    StringCommandComponentInterface,
    UltrasoundInterface,
)

Call = tuple[str, tuple[object, ...]]


class Recorder:
    """Concrete versions of every interface method a board test needs."""

    board: ClassVar[type[Board]]

    def __init__(self) -> None:
        self.calls: list[Call] = []
        self.leds: dict[int, bool] = {}
        self.outputs: dict[int, bool] = {}
        self.motors: dict[int, MotorState] = {}
        self.servos: dict[int, ServoPosition] = {}
        self.pin_modes: dict[int, GPIOPinMode] = {}
        self.button_polls = 0
        #: get_button_state answers True from this poll on (counting from 1).
        self.pressed_on_poll: int | None = None
        #: wait_until_button_pressed waits for this event, if there is one.
        self.press: anyio.Event | None = None
        self.closed = False

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        return [cls.board("FAKE1", cls())]  # type: ignore[arg-type]

    @property
    def firmware_version(self) -> str | None:
        return "fake-1"

    async def close(self) -> None:
        self.closed = True

    def _record(self, method: str, *args: object) -> None:
        self.calls.append((method, args))

    def named(self, method: str) -> list[tuple[object, ...]]:
        """The arguments of every call to ``method``, in order."""
        return [args for name, args in self.calls if name == method]

    async def get_led_state(self, identifier: int) -> bool:
        return self.leds.get(identifier, False)

    async def set_led_state(self, identifier: int, state: bool) -> None:
        self._record("set_led_state", identifier, state, self.button_polls)
        self.leds[identifier] = state

    async def get_button_state(self, identifier: int) -> bool:
        self.button_polls += 1
        self._record("get_button_state", identifier)
        return self.pressed_on_poll is not None and self.button_polls >= self.pressed_on_poll

    async def wait_until_button_pressed(self, identifier: int) -> None:
        self._record("wait_until_button_pressed", identifier)
        if self.press is not None:
            await self.press.wait()

    async def get_power_output_enabled(self, identifier: int) -> bool:
        return self.outputs.get(identifier, False)

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        self._record("set_power_output_enabled", identifier, enabled)
        self.outputs[identifier] = enabled

    async def get_power_output_current(self, identifier: int) -> float:
        return 0.5

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        self._record("buzz", identifier, duration, pitch)

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        return 12.0

    async def get_battery_sensor_current(self, identifier: int) -> float:
        return 1.5

    async def get_motor_state(self, identifier: int) -> MotorState:
        return self.motors[identifier]

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        self._record("set_motor_state", identifier, power)
        self.motors[identifier] = power

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        return self.servos.get(identifier)

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        self._record("set_servo_position", identifier, position)
        self.servos[identifier] = position

    async def execute_string_command(self, command: str) -> str:
        self._record("execute_string_command", command)
        return command.upper()

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        self._record("set_gpio_pin_mode", identifier, pin_mode)
        self.pin_modes[identifier] = pin_mode

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        return self.pin_modes[identifier]

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        self._record("write_gpio_pin_digital_state", identifier, state)

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        return False

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        return True

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        return 2.5

    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        self._record("write_gpio_pin_dac_value", identifier, scaled_value)

    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        self._record("write_gpio_pin_pwm_value", identifier, duty_cycle)

    async def get_ultrasound_pulse(self, trigger: int, echo: int) -> timedelta | None:
        self._record("get_ultrasound_pulse", trigger, echo)
        return timedelta(microseconds=580)

    async def get_ultrasound_distance(self, trigger: int, echo: int) -> float | None:
        self._record("get_ultrasound_distance", trigger, echo)
        return 0.1


class FakePowerBoardBackend(
    Recorder,
    PowerOutputInterface,
    PiezoInterface,
    ButtonInterface,
    BatterySensorInterface,
    LEDInterface,
    Backend,
):
    board = PowerBoard


class FakeMotorBoardBackend(Recorder, MotorInterface, Backend):
    board = MotorBoard


class FakeServoBoardBackend(Recorder, ServoInterface, Backend):
    board = ServoBoard


class FakeUnoBackend(Recorder, GPIOPinInterface, LEDInterface, Backend):
    board = ArduinoUno


class FakeRuggeduinoBackend(
    Recorder, StringCommandComponentInterface, GPIOPinInterface, LEDInterface, Backend,
):
    board = Ruggeduino


class FakeSBArduinoBackend(
    Recorder, ServoInterface, UltrasoundInterface, GPIOPinInterface, LEDInterface, Backend,
):
    board = SBArduinoBoard


class FakeSRArduinoBackend(
    Recorder,
    StringCommandComponentInterface,
    UltrasoundInterface,
    GPIOPinInterface,
    LEDInterface,
    Backend,
):
    board = SRArduinoBoard
