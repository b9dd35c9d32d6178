from __future__ import annotations

import pytest

from j5aio.boards.arduino import AnaloguePin, ArduinoUno
from j5aio.boards.sr.v4 import Ruggeduino
from j5aio.components import LED, GPIOPin, GPIOPinMode, StringCommandComponent
from j5aio.errors import NotSupportedByComponentError

from .board_fakes import FakeRuggeduinoBackend, FakeUnoBackend

DIGITAL_MODES = {
    GPIOPinMode.DIGITAL_INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP,
    GPIOPinMode.DIGITAL_OUTPUT,
}


def test_identity() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    assert ArduinoUno.name == "Arduino Uno"
    assert board.serial_number == "U1"
    assert board.firmware_version == "fake-1"
    assert repr(board) == "<ArduinoUno serial_number='U1'>"
    assert ArduinoUno.supported_components() == {GPIOPin, LED}


def test_analogue_pin_numbers() -> None:
    assert ArduinoUno.AnaloguePin is AnaloguePin
    assert [(p.name, int(p)) for p in AnaloguePin] == [
        ("A0", 14), ("A1", 15), ("A2", 16), ("A3", 17), ("A4", 18), ("A5", 19),
    ]


def test_pins_by_number_and_by_analogue_name() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    assert sorted(board.pins.keys()) == list(range(2, 20))
    assert 0 not in board.pins and 1 not in board.pins and 20 not in board.pins
    assert board.pins[AnaloguePin.A3] is board.pins[17]
    assert board.pins[17].identifier == 17
    assert type(board.pins[17].identifier) is int
    for number in range(2, 14):
        assert board.pins[number].identifier == number
        assert board.pins[number].hardware_modes == DIGITAL_MODES
        assert board.pins[number].firmware_modes == frozenset()
    for pin in AnaloguePin:
        assert board.pins[pin].hardware_modes == {GPIOPinMode.ANALOGUE_INPUT}


def test_pins_are_read_only() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    with pytest.raises(TypeError):
        board.pins[2] = board.pins[3]  # type: ignore[index]
    with pytest.raises(AttributeError):
        board.pins = {}  # type: ignore[misc, assignment]
    with pytest.raises(AttributeError):
        board.led = board.led  # type: ignore[misc]


async def test_setup_applies_every_initial_mode_in_pin_order() -> None:
    backend = FakeUnoBackend()
    board = ArduinoUno("U1", backend)
    await board.setup()
    assert backend.named("set_gpio_pin_mode") == [
        *((n, GPIOPinMode.DIGITAL_INPUT) for n in range(2, 14)),
        *((n, GPIOPinMode.ANALOGUE_INPUT) for n in range(14, 20)),
    ]
    await board.setup()  # only once
    assert len(backend.named("set_gpio_pin_mode")) == 18
    assert await board.pins[AnaloguePin.A0].analogue_read() == 2.5


async def test_digital_pins_have_no_analogue_input() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    with pytest.raises(NotSupportedByComponentError):
        await board.pins[2].set_mode(GPIOPinMode.ANALOGUE_INPUT)


async def test_led_is_led_zero() -> None:
    backend = FakeUnoBackend()
    board = ArduinoUno("U1", backend)
    await board.led.set_state(True)
    assert backend.leds == {0: True}


async def test_make_safe_does_nothing() -> None:
    backend = FakeUnoBackend()
    board = ArduinoUno("U1", backend)
    await board.make_safe()
    assert backend.calls == []


def test_ruggeduino_is_an_uno_with_a_string_command() -> None:
    board = Ruggeduino("R1", FakeRuggeduinoBackend())
    assert isinstance(board, ArduinoUno)
    assert Ruggeduino.name == "Ruggeduino"
    assert Ruggeduino.supported_components() == {GPIOPin, LED, StringCommandComponent}
    assert isinstance(board.command, StringCommandComponent)
    assert sorted(board.pins.keys()) == list(range(2, 20))
    with pytest.raises(AttributeError):
        board.command = board.command  # type: ignore[misc]


async def test_ruggeduino_command_reaches_the_backend() -> None:
    backend = FakeRuggeduinoBackend()
    board = Ruggeduino("R1", backend)
    assert await board.command.execute("ping") == "PING"
    assert backend.named("execute_string_command") == [("ping",)]


async def test_digital_mode_on_an_analogue_pin_is_refused_by_the_pin() -> None:
    board = ArduinoUno("UNO", FakeUnoBackend())
    with pytest.raises(NotSupportedByComponentError, match="ANALOGUE_INPUT"):
        await board.pins[AnaloguePin.A0].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
