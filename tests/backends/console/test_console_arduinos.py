from __future__ import annotations

from datetime import timedelta

import pytest

from j5aio.backends.console.sb import SBArduinoConsoleBackend
from j5aio.backends.console.sr.v4 import SRV4RuggeduinoConsoleBackend
from j5aio.boards.arduino import AnaloguePin
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import Ruggeduino
from j5aio.components import GPIOPinMode
from j5aio.errors import BadGPIOPinModeError, NotSupportedByHardwareError

from .console_script import Terminal

RUGGEDUINO = "Ruggeduino(SERIAL): "
SB = "SBArduinoBoard(SERIAL): "


async def ruggeduino(terminal: Terminal) -> Ruggeduino:
    board = Ruggeduino("SERIAL", SRV4RuggeduinoConsoleBackend("SERIAL", terminal.console_class()))
    await board.setup()
    terminal.lines.clear()
    return board


async def test_setup_prints_each_initial_mode() -> None:
    terminal = Terminal()
    board = Ruggeduino("SERIAL", SRV4RuggeduinoConsoleBackend("SERIAL", terminal.console_class()))
    await board.setup()
    assert terminal.lines == [
        *(f"{RUGGEDUINO}Set pin {n} to DIGITAL_INPUT" for n in range(2, 14)),
        *(f"{RUGGEDUINO}Set pin {n} to ANALOGUE_INPUT" for n in range(14, 20)),
    ]
    assert await board.pins[2].get_mode() is GPIOPinMode.DIGITAL_INPUT
    assert await board.pins[AnaloguePin.A5].get_mode() is GPIOPinMode.ANALOGUE_INPUT


async def test_digital_output_is_printed_and_remembered() -> None:
    terminal = Terminal()
    board = await ruggeduino(terminal)
    pin = board.pins[7]
    await pin.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await pin.digital_write(True)
    assert await pin.get_last_digital_write() is True
    assert terminal.lines == [
        RUGGEDUINO + "Set pin 7 to DIGITAL_OUTPUT",
        RUGGEDUINO + "Set pin 7 state to True",
    ]


async def test_digital_and_analogue_reads_are_asked_for() -> None:
    terminal = Terminal(["maybe", "true", "3.3"])
    board = await ruggeduino(terminal)
    assert await board.pins[2].digital_read() is True
    assert await board.pins[AnaloguePin.A0].analogue_read() == 3.3
    assert terminal.lines == [
        RUGGEDUINO + "Pin 2 digital state [true/false]: ",
        RUGGEDUINO + "Unable to construct a bool from 'maybe'",
        RUGGEDUINO + "Pin 2 digital state [true/false]: ",
        RUGGEDUINO + "Pin 14 ADC state [float]: ",
    ]


async def test_pullup_input_can_be_read() -> None:
    terminal = Terminal(["false"])
    board = await ruggeduino(terminal)
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    assert await board.pins[3].digital_read() is False


async def test_string_command_reply_is_asked_for() -> None:
    terminal = Terminal(["pong"])
    board = await ruggeduino(terminal)
    assert await board.command.execute("ping") == "pong"
    assert terminal.prompts == [RUGGEDUINO + 'Response to string command "ping" [str]: ']


async def test_led_is_pin_13() -> None:
    terminal = Terminal()
    board = await ruggeduino(terminal)
    with pytest.raises(BadGPIOPinModeError, match="pin 13 is in mode DIGITAL_INPUT"):
        await board.led.set_state(True)
    await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.led.set_state(True)
    assert await board.led.get_state() is True
    assert terminal.lines[-1] == RUGGEDUINO + "Set pin 13 state to True"


@pytest.mark.parametrize("identifier", [1, -1])
async def test_unknown_led(identifier: int) -> None:
    backend = SRV4RuggeduinoConsoleBackend("SERIAL", Terminal().console_class())
    with pytest.raises(ValueError, match="only LED 0"):
        await backend.set_led_state(identifier, True)
    with pytest.raises(ValueError, match="only LED 0"):
        await backend.get_led_state(identifier)


async def test_backend_checks_the_pin_mode_itself() -> None:
    terminal = Terminal()
    backend = SRV4RuggeduinoConsoleBackend("SERIAL", terminal.console_class())
    await backend.set_gpio_pin_mode(5, GPIOPinMode.DIGITAL_INPUT)
    with pytest.raises(BadGPIOPinModeError, match="DIGITAL_OUTPUT"):
        await backend.write_gpio_pin_digital_state(5, True)
    with pytest.raises(BadGPIOPinModeError, match="DIGITAL_OUTPUT"):
        await backend.get_gpio_pin_digital_state(5)
    with pytest.raises(BadGPIOPinModeError, match="ANALOGUE_INPUT"):
        await backend.read_gpio_pin_analogue_value(5)
    await backend.set_gpio_pin_mode(5, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(BadGPIOPinModeError, match="DIGITAL_INPUT"):
        await backend.read_gpio_pin_digital_state(5)
    assert terminal.prompts == []


@pytest.mark.parametrize(
    ("pin", "mode"),
    [
        (5, GPIOPinMode.ANALOGUE_INPUT),
        (5, GPIOPinMode.DIGITAL_INPUT_PULLDOWN),
        (14, GPIOPinMode.ANALOGUE_OUTPUT),
        (9, GPIOPinMode.PWM_OUTPUT),
    ],
)
async def test_modes_the_uno_lacks(pin: int, mode: GPIOPinMode) -> None:
    terminal = Terminal()
    backend = SRV4RuggeduinoConsoleBackend("SERIAL", terminal.console_class())
    with pytest.raises(NotSupportedByHardwareError, match=mode.name):
        await backend.set_gpio_pin_mode(pin, mode)
    assert terminal.lines == []


async def test_no_dac_and_no_pwm() -> None:
    backend = SRV4RuggeduinoConsoleBackend("SERIAL", Terminal().console_class())
    with pytest.raises(NotSupportedByHardwareError, match="no DAC"):
        await backend.write_gpio_pin_dac_value(14, 0.5)
    with pytest.raises(NotSupportedByHardwareError, match="PWM"):
        await backend.write_gpio_pin_pwm_value(9, 0.5)


@pytest.mark.parametrize("identifier", [0, 1, 20])
async def test_unknown_pins(identifier: int) -> None:
    backend = SRV4RuggeduinoConsoleBackend("SERIAL", Terminal().console_class())
    with pytest.raises(ValueError, match=r"invalid pin identifier .* 2 to 19"):
        await backend.get_gpio_pin_mode(identifier)
    with pytest.raises(ValueError, match="invalid pin identifier"):
        await backend.set_gpio_pin_mode(identifier, GPIOPinMode.DIGITAL_OUTPUT)


async def sb_arduino(terminal: Terminal) -> SBArduinoBoard:
    board = SBArduinoBoard("SERIAL", SBArduinoConsoleBackend("SERIAL", terminal.console_class()))
    await board.setup()
    terminal.lines.clear()
    return board


async def test_sb_servos_are_printed() -> None:
    terminal = Terminal()
    board = await sb_arduino(terminal)
    assert await board.servos[15].get_position() is None
    await board.servos[15].set_position(-0.5)
    await board.servos[0].set_position(None)
    assert await board.servos[15].get_position() == -0.5
    assert terminal.lines == [SB + "Set servo 15 to -0.5", SB + "Set servo 0 to None"]


@pytest.mark.parametrize("identifier", [-1, 16])
async def test_sb_unknown_servo(identifier: int) -> None:
    backend = SBArduinoConsoleBackend("SERIAL", Terminal().console_class())
    with pytest.raises(ValueError, match=r"invalid servo identifier .* 0 to 15"):
        await backend.set_servo_position(identifier, 0.0)
    with pytest.raises(ValueError, match="invalid servo identifier"):
        await backend.get_servo_position(identifier)


async def test_sb_ultrasound_is_asked_for_and_sets_the_pin_modes() -> None:
    terminal = Terminal(["580", "0.1"])
    board = await sb_arduino(terminal)
    sensor = board.ultrasound_sensors[4, 5]
    assert await sensor.pulse() == timedelta(microseconds=580)
    assert await sensor.distance() == 0.1
    assert terminal.prompts == [
        SB + "Response time for ultrasound sensor on pins 4/5 [microseconds]: ",
        SB + "Distance for ultrasound sensor on pins 4/5 [metres]: ",
    ]
    assert await board.pins[4].get_mode() is GPIOPinMode.DIGITAL_OUTPUT
    assert await board.pins[4].get_last_digital_write() is False
    assert await board.pins[5].get_mode() is GPIOPinMode.DIGITAL_INPUT


async def test_sb_ultrasound_on_unknown_pins() -> None:
    terminal = Terminal()
    backend = SBArduinoConsoleBackend("SERIAL", terminal.console_class())
    with pytest.raises(ValueError, match="invalid pin identifier"):
        await backend.get_ultrasound_distance(4, 30)
    with pytest.raises(ValueError, match="invalid pin identifier"):
        await backend.get_ultrasound_pulse(1, 5)
    assert terminal.prompts == []
