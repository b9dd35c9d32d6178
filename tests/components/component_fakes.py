"""A small recording backend for the component tests.

It implements every component interface, records each call as ``(method, args)`` in
``calls``, and keeps just enough state that a write can be read back.

(It lives in a module of its own rather than in a ``conftest.py``, so that the test
modules can import it, relatively, for their type annotations.)
"""

from __future__ import annotations

from datetime import timedelta

import anyio

from j5aio.components import (
    BatterySensorInterface,
    ButtonInterface,
    GPIOPinInterface,
    GPIOPinMode,
    LEDInterface,
    MotorInterface,
    MotorSpecialState,
    MotorState,
    PiezoInterface,
    PowerOutputInterface,
    RGBChannel,
    RGBLEDInterface,
    ServoInterface,
    ServoPosition,
    StringCommandComponentInterface,
    UltrasoundInterface,
)
from j5aio.errors import CommunicationError

Call = tuple[str, tuple[object, ...]]


class RecordingBackend(
    LEDInterface,
    ButtonInterface,
    MotorInterface,
    ServoInterface,
    PiezoInterface,
    PowerOutputInterface,
    BatterySensorInterface,
    StringCommandComponentInterface,
    GPIOPinInterface,
    RGBLEDInterface,
    UltrasoundInterface,
):
    """Every interface at once; each call is appended to :attr:`calls`."""

    def __init__(self) -> None:
        self.calls: list[Call] = []
        self.led = False
        self.pressed = anyio.Event()
        self.wait_cancelled = False
        self.motor: MotorState = MotorSpecialState.COAST
        self.servo: ServoPosition = None
        self.enabled: dict[int, bool] = {}
        self.broken_outputs: set[int] = set()
        self.current = 1.25
        self.voltage = 11.5
        self.pin_mode = GPIOPinMode.DIGITAL_OUTPUT
        self.pin_level = False
        self.analogue = 2.5
        self.duty = dict.fromkeys(RGBChannel, 0.0)
        self.echo: timedelta | None = timedelta(milliseconds=3)
        self.distance: float | None = 0.5

    def _record(self, method: str, *args: object) -> None:
        self.calls.append((method, args))

    def names(self) -> list[str]:
        """The names of the methods called, in order."""
        return [name for name, _ in self.calls]

    async def get_led_state(self, identifier: int) -> bool:
        self._record("get_led_state", identifier)
        return self.led

    async def set_led_state(self, identifier: int, state: bool) -> None:
        self._record("set_led_state", identifier, state)
        self.led = state

    async def get_button_state(self, identifier: int) -> bool:
        self._record("get_button_state", identifier)
        return self.pressed.is_set()

    async def wait_until_button_pressed(self, identifier: int) -> None:
        self._record("wait_until_button_pressed", identifier)
        try:
            await self.pressed.wait()
        except anyio.get_cancelled_exc_class():
            self.wait_cancelled = True
            raise

    async def get_motor_state(self, identifier: int) -> MotorState:
        self._record("get_motor_state", identifier)
        return self.motor

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        self._record("set_motor_state", identifier, power)
        self.motor = power

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        self._record("get_servo_position", identifier)
        return self.servo

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        self._record("set_servo_position", identifier, position)
        self.servo = position

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        self._record("buzz", identifier, duration, pitch)

    async def get_power_output_enabled(self, identifier: int) -> bool:
        self._record("get_power_output_enabled", identifier)
        return self.enabled.get(identifier, False)

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        self._record("set_power_output_enabled", identifier, enabled)
        if identifier in self.broken_outputs:
            raise CommunicationError(f"output {identifier} did not answer")
        self.enabled[identifier] = enabled

    async def get_power_output_current(self, identifier: int) -> float:
        self._record("get_power_output_current", identifier)
        return self.current

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        self._record("get_battery_sensor_voltage", identifier)
        return self.voltage

    async def get_battery_sensor_current(self, identifier: int) -> float:
        self._record("get_battery_sensor_current", identifier)
        return self.current

    async def execute_string_command(self, command: str) -> str:
        self._record("execute_string_command", command)
        return command[::-1]

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        self._record("set_gpio_pin_mode", identifier, pin_mode)
        self.pin_mode = pin_mode

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        self._record("get_gpio_pin_mode", identifier)
        return self.pin_mode

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        self._record("write_gpio_pin_digital_state", identifier, state)
        self.pin_level = state

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        self._record("get_gpio_pin_digital_state", identifier)
        return self.pin_level

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        self._record("read_gpio_pin_digital_state", identifier)
        return self.pin_level

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        self._record("read_gpio_pin_analogue_value", identifier)
        return self.analogue

    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        self._record("write_gpio_pin_dac_value", identifier, scaled_value)

    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        self._record("write_gpio_pin_pwm_value", identifier, duty_cycle)

    async def get_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel,
    ) -> float:
        self._record("get_rgb_led_channel_duty_cycle", identifier, channel)
        return self.duty[channel]

    async def set_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel, duty_cycle: float,
    ) -> None:
        self._record("set_rgb_led_channel_duty_cycle", identifier, channel, duty_cycle)
        self.duty[channel] = duty_cycle

    async def get_ultrasound_pulse(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> timedelta | None:
        self._record("get_ultrasound_pulse", trigger_pin_identifier, echo_pin_identifier)
        return self.echo

    async def get_ultrasound_distance(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> float | None:
        self._record("get_ultrasound_distance", trigger_pin_identifier, echo_pin_identifier)
        return self.distance
