from __future__ import annotations

from collections.abc import Iterator
from datetime import timedelta

import anyio
import pytest

from j5aio.backends.console import Console, ConsoleBackend
from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard, PowerOutputPosition
from j5aio.components import Note
from j5aio.errors import NotSupportedByHardwareError

from .console_script import Terminal

PREFIX = "PowerBoard(SERIAL): "


@pytest.fixture
def terminal() -> Terminal:
    return Terminal()


@pytest.fixture
def backend(terminal: Terminal) -> SRV4PowerBoardConsoleBackend:
    return SRV4PowerBoardConsoleBackend("SERIAL", terminal.console_class())


@pytest.fixture
def board(backend: SRV4PowerBoardConsoleBackend) -> PowerBoard:
    return PowerBoard("SERIAL", backend)


@pytest.fixture
def default_console(terminal: Terminal) -> Iterator[None]:
    saved = ConsoleBackend.console_class
    ConsoleBackend.console_class = terminal.console_class()
    try:
        yield
    finally:
        ConsoleBackend.console_class = saved


async def test_discover_finds_one_board_serial_serial(
    default_console: None, terminal: Terminal,
) -> None:
    boards = await SRV4PowerBoardConsoleBackend.discover()
    assert len(boards) == 1
    (board,) = boards
    assert isinstance(board, PowerBoard)
    assert board.serial_number == "SERIAL"
    assert board.firmware_version is None
    assert board not in PowerBoard.BOARDS  # discovery does not set boards up
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardConsoleBackend)
    assert backend.serial == "SERIAL"
    assert backend.console.descriptor == "PowerBoard(SERIAL)"
    await board.run_led.set_state(True)
    assert terminal.lines == [PREFIX + "Set LED 0 to True"]


def test_console_class_from_the_constructor_wins(terminal: Terminal) -> None:
    backend = SRV4PowerBoardConsoleBackend("X", terminal.console_class())
    assert type(backend.console).__name__ == "ScriptedConsole"
    assert type(SRV4PowerBoardConsoleBackend("X").console) is Console


async def test_outputs_are_printed_and_remembered(
    board: PowerBoard, terminal: Terminal,
) -> None:
    assert await board.outputs[PowerOutputPosition.H1].get_is_enabled() is False
    await board.outputs[PowerOutputPosition.H1].set_is_enabled(True)
    assert await board.outputs[PowerOutputPosition.H1].get_is_enabled() is True
    await board.make_safe()
    assert terminal.lines == [
        PREFIX + "Setting output 1 to True",
        *(PREFIX + f"Setting output {i} to False" for i in range(6)),
    ]


async def test_output_current_is_asked_for(board: PowerBoard, terminal: Terminal) -> None:
    terminal.answer("lots", "2.5")
    assert await board.outputs[PowerOutputPosition.L3].get_current() == 2.5
    assert terminal.lines == [
        PREFIX + "Current for power output 5 [amps]: ",
        PREFIX + "Unable to construct a float from 'lots'",
        PREFIX + "Current for power output 5 [amps]: ",
    ]


async def test_battery_is_asked_for(board: PowerBoard, terminal: Terminal) -> None:
    terminal.answer("11.9", "0.75")
    assert await board.battery_sensor.get_voltage() == 11.9
    assert await board.battery_sensor.get_current() == 0.75
    assert terminal.prompts == [
        PREFIX + "Battery voltage [volts]: ",
        PREFIX + "Battery current [amps]: ",
    ]


async def test_buzz_is_printed(board: PowerBoard, terminal: Terminal) -> None:
    await board.piezo.buzz(0.5, 440)
    await board.piezo.buzz(timedelta(milliseconds=100), Note.A6)
    assert terminal.lines == [
        PREFIX + "Buzzing at 440.0Hz for 500ms",
        PREFIX + "Buzzing at 1760.0Hz for 100ms",
    ]


async def test_buzz_longer_than_the_board_can_play(
    backend: SRV4PowerBoardConsoleBackend, terminal: Terminal,
) -> None:
    with pytest.raises(NotSupportedByHardwareError, match="65535 ms"):
        await backend.buzz(0, timedelta(seconds=66), 440.0)
    await backend.buzz(0, timedelta(milliseconds=65535), 440.0)
    assert terminal.lines == [PREFIX + "Buzzing at 440.0Hz for 65535ms"]


async def test_start_button_state_is_asked_for(board: PowerBoard, terminal: Terminal) -> None:
    terminal.answer("yes", "false")
    assert await board.start_button.get_is_pressed() is True
    assert await board.start_button.get_is_pressed() is False
    assert terminal.prompts == [PREFIX + "Start button state [true/false]: "] * 2


async def test_wait_until_pressed_waits_for_return(board: PowerBoard, terminal: Terminal) -> None:
    terminal.answer("")
    await board.start_button.wait_until_pressed()
    assert terminal.lines == [
        PREFIX + "Waiting for start button press.",
        PREFIX + "Hit return to press start button: ",
    ]


async def test_wait_until_pressed_at_end_of_input(board: PowerBoard) -> None:
    with pytest.raises(EOFError, match="ran out of input"):
        await board.start_button.wait_until_pressed()


async def test_wait_for_start_flash_on_the_console(
    board: PowerBoard, terminal: Terminal,
) -> None:
    terminal.answer("false", "true")
    with anyio.fail_after(5):
        await board.wait_for_start_flash()
    assert [line for line in terminal.lines if "LED" in line] == [
        PREFIX + "Set LED 0 to True",
        PREFIX + "Set LED 0 to True",
    ]


async def test_leds(board: PowerBoard, terminal: Terminal) -> None:
    await board.error_led.set_state(True)
    assert await board.error_led.get_state() is True
    assert await board.run_led.get_state() is False
    assert terminal.lines == [PREFIX + "Set LED 1 to True"]


@pytest.mark.parametrize(
    ("call", "kind"),
    [
        (lambda b: b.get_power_output_enabled(6), "power output"),
        (lambda b: b.set_power_output_enabled(-1, True), "power output"),
        (lambda b: b.get_power_output_current(6), "power output"),
        (lambda b: b.buzz(1, timedelta(seconds=1), 440.0), "piezo"),
        (lambda b: b.get_button_state(1), "button"),
        (lambda b: b.wait_until_button_pressed(1), "button"),
        (lambda b: b.get_battery_sensor_voltage(1), "battery sensor"),
        (lambda b: b.get_battery_sensor_current(1), "battery sensor"),
        (lambda b: b.get_led_state(2), "LED"),
        (lambda b: b.set_led_state(2, True), "LED"),
    ],
)
async def test_unknown_identifiers(
    backend: SRV4PowerBoardConsoleBackend, terminal: Terminal, call: object, kind: str,
) -> None:
    with pytest.raises(ValueError, match=f"invalid {kind} identifier"):
        await call(backend)  # type: ignore[operator]
    assert terminal.lines == []
