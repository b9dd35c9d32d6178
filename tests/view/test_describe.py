"""How the view names components and turns interface calls into values."""

from __future__ import annotations

import math
from datetime import timedelta
from typing import Any

from j5aio.boards.sr.kch import KCHBoard
from j5aio.components.flashing_led import LEDMode
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.components.piezo import Note
from j5aio.components.rgb_led import RGBChannel
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.view.describe import (
    ComponentInfo,
    Update,
    board_components,
    component_id,
    component_names,
    describe_call,
    jsonable,
)


async def test_every_component_of_the_sr2019_kit_is_found() -> None:
    use_kit(KitConfig(motor_boards=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        power = board_components(robot.power_board)
        assert ComponentInfo("motor", "0") not in power
        kinds = {c.kind for c in power}
        assert kinds == {"batterysensor", "button", "led", "piezo", "poweroutput"}
        assert [c.identifier for c in power if c.kind == "poweroutput"] == [
            str(i) for i in range(6)
        ]
        motors = board_components(robot.motor_boards[0])
        assert motors == [ComponentInfo("motor", "0"), ComponentInfo("motor", "1")]
        arduino = board_components(robot.arduinos[0])
        pins = [c.identifier for c in arduino if c.kind == "gpiopin"]
        assert pins == [str(i) for i in range(2, 20)]  # in number order, not text order
        assert len([c for c in arduino if c.kind == "servo"]) == 16
        assert component_id("SIMSBA0", ComponentInfo("gpiopin", "14")) == "SIMSBA0:gpiopin:14"


async def test_calls_become_values() -> None:
    use_kit(KitConfig(motor_boards=1, power_boards=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        motor_board, power, arduino = robot.motor_boards[0], robot.power_board, robot.arduinos[0]

        def call(board: Any, method: str, *arguments: Any, result: Any = None) -> Update | None:
            return describe_call(board, method, arguments, result, board_components(board))

        assert call(motor_board, "set_motor_state", 1, 0.5) == Update(
            "motor", "1", "motor_state", 0.5
        )
        assert call(motor_board, "set_motor_state", 0, MotorSpecialState.BRAKE) == Update(
            "motor", "0", "motor_state", "BRAKE"
        )
        assert call(motor_board, "get_motor_state", 0, result=-0.25) == Update(
            "motor", "0", "motor_state", -0.25
        )
        assert call(power, "get_power_output_current", 3, result=1.5) == Update(
            "poweroutput", "3", "power_output_current", 1.5
        )
        assert call(power, "wait_until_button_pressed", 0) == Update(
            "button", "0", "button_state", True
        )
        assert call(power, "buzz", 0, timedelta(seconds=0.25), Note.A6) == Update(
            "piezo", "0", "note", {"pitch": 1760.0, "seconds": 0.25}
        )
        assert call(arduino, "get_ultrasound_distance", 6, 7, result=0.5) == Update(
            "ultrasoundsensor", "6-7", "ultrasound_distance", 0.5
        )
        assert call(arduino, "get_gpio_pin_mode", 14, result=GPIOPinMode.ANALOGUE_INPUT) == Update(
            "gpiopin", "14", "gpio_pin_mode", "ANALOGUE_INPUT"
        )
        # an LED of the Arduino and its servos share no method with the pins
        assert call(arduino, "set_led_state", 0, True) == Update("led", "0", "led_state", True)
        # calls that show nothing
        assert call(arduino, "not_an_interface_method", 1) is None
        assert call(motor_board, "get_motor_state") is None


def test_extra_arguments_name_the_field() -> None:
    # describe_call looks only at the board's class (and the components it is given)
    kch = object.__new__(KCHBoard)
    assert describe_call(
        kch, "set_rgb_led_channel_duty_cycle", (1, RGBChannel.GREEN, 1.0), None
    ) == (Update("rgbled", "1", "rgb_led_channel_duty_cycle.green", 1.0))
    assert describe_call(kch, "get_rgb_led_channel_duty_cycle", (2, RGBChannel.RED), 0.0) == (
        Update("rgbled", "2", "rgb_led_channel_duty_cycle.red", 0.0)
    )
    assert describe_call(kch, "set_led_mode", (0, LEDMode.FLASH), None) == (
        Update("flashingled", "0", "led_mode", "FLASH")
    )


def test_values_as_json() -> None:
    assert jsonable(None) is None
    assert jsonable(True) is True
    assert jsonable(3) == 3
    assert jsonable(GPIOPinMode.DIGITAL_OUTPUT) == "DIGITAL_OUTPUT"
    assert jsonable(Note.C6) == 1047.0 and type(jsonable(Note.C6)) is float
    assert jsonable(math.nan) == "nan"
    assert jsonable("text") == "text"
    assert jsonable(timedelta(milliseconds=1500)) == 1.5
    assert jsonable((1, MotorSpecialState.COAST)) == [1, "COAST"]
    assert jsonable(object()).startswith("<object")


def test_a_flashing_leds_state_is_shown_as_its_mode() -> None:
    kch = object.__new__(KCHBoard)
    assert describe_call(kch, "set_led_state", (0, True), None) == (
        Update("flashingled", "0", "led_mode", "ON")
    )
    assert describe_call(kch, "set_led_state", (0, False), None) == (
        Update("flashingled", "0", "led_mode", "OFF")
    )
    # A read of whether it is lit (a flashing LED is) is not its mode.
    assert describe_call(kch, "get_led_state", (0,), True) == (
        Update("flashingled", "0", "led_state", True)
    )
    assert describe_call(kch, "get_led_mode", (0,), LEDMode.FLASH) == (
        Update("flashingled", "0", "led_mode", "FLASH")
    )


async def test_the_kch_of_the_sr2023_kit_and_its_named_components() -> None:
    use_kit("sr2023")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.kch is not None
        assert board_components(robot.kch) == [
            ComponentInfo("flashingled", "0"),
            ComponentInfo("rgbled", "0"),
            ComponentInfo("rgbled", "1"),
            ComponentInfo("rgbled", "2"),
        ]
        # Components that are board properties of their own are named by them, in words.
        assert component_names(robot.kch) == {ComponentInfo("flashingled", "0"): "start LED"}
        names = component_names(robot.power_board)
        assert names[ComponentInfo("flashingled", "0")] == "run LED"
        assert names[ComponentInfo("flashingled", "1")] == "error LED"
        assert names[ComponentInfo("button", "0")] == "start button"
