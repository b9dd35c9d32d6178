from __future__ import annotations

import pytest

from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SBServoBoardConsoleBackend,
    SRV4ServoBoardFw4ConsoleBackend,
)
from j5aio.boards.sb import SBServoBoard
from j5aio.boards.sr.kch import Colour, KCHBoard
from j5aio.boards.sr.v4 import ServoBoardFw4
from j5aio.components.flashing_led import LEDMode
from j5aio.components.rgb_led import RGBChannel

from .console_script import Terminal


async def test_servos_print_moves_and_read_back_in_5us_steps() -> None:
    terminal = Terminal()
    backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", terminal.console_class())
    board = ServoBoardFw4("SERIAL", backend)
    assert len(board.servos) == 12
    assert await board.servos[0].get_position() is None
    await board.servos[0].set_position(0.333)
    assert await board.servos[0].get_pulse_width() == 1665
    assert await board.servos[0].get_position() == 0.33
    await board.servos[1].set_pulse_limits(500, 2500)
    await board.servos[1].set_position(-1)
    assert await board.servos[1].get_pulse_width() == 500
    assert await board.servos[1].get_pulse_limits() == (500, 2500)
    await board.servos[0].set_position(None)
    assert await board.servos[0].get_position() is None
    assert terminal.lines == [
        "ServoBoardFw4(SERIAL): Setting servo 0 to 0.333 (1666 µs).",
        "ServoBoardFw4(SERIAL): Servo 1 now spans 500 to 2500 µs.",
        "ServoBoardFw4(SERIAL): Setting servo 1 to -1.0 (500 µs).",
        "ServoBoardFw4(SERIAL): Setting servo 0 to unpowered.",
    ]


async def test_the_fork_has_eight_servos_from_300us() -> None:
    terminal = Terminal()
    board = SBServoBoard("SERIAL", SBServoBoardConsoleBackend("SERIAL", terminal.console_class()))
    assert len(board.servos) == 8
    assert await board.servos[7].get_pulse_range() == (300, 4000)
    assert await board.servos[0].get_pulse_limits() == (350, 1980)  # sbot's defaults
    await board.servos[7].set_pulse_limits(300, 400)
    with pytest.raises(ValueError, match="invalid servo identifier 8"):
        await board.backend.get_servo_pulse_limits(8)  # type: ignore[attr-defined]


async def test_backend_refuses_limits_outside_the_firmware_range() -> None:
    backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", Terminal().console_class())
    with pytest.raises(ValueError, match="500 to 4000"):
        await backend.set_servo_pulse_limits(0, (300, 2000))


async def test_supply_and_flags_are_asked_for() -> None:
    terminal = Terminal(["5.5", "0.75", "true", "false"])
    backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", terminal.console_class())
    board = ServoBoardFw4("SERIAL", backend)
    assert await board.supply.get_voltage() == 5.5
    assert await board.supply.get_current() == 0.75
    assert await board.power_good.get_state() is True
    assert await board.watchdog_failed.get_state() is False
    assert [prompt.split(": ", 1)[1] for prompt in terminal.prompts] == [
        "Servo supply voltage [volts]: ", "Servo supply current [amps]: ",
        "Power good [true/false]: ", "Watchdog failed [true/false]: ",
    ]


async def test_kch_prints_colours_and_the_start_led() -> None:
    terminal = Terminal()
    board = KCHBoard("SERIAL", KCHConsoleBackend("SERIAL", terminal.console_class()))
    await board.leds[0].set_colour(Colour.CYAN)
    assert await board.leds[0].get_colour() == Colour.CYAN
    await board.leds[2].set_red(0.2)
    assert await board.leds[2].get_red() == 1.0
    await board.start_led.flash()
    assert await board.start_led.get_mode() is LEDMode.FLASH
    assert await board.start_led.get_state()  # a flashing LED reads as lit
    await board.make_safe()
    assert await board.start_led.get_mode() is LEDMode.OFF
    assert terminal.lines == [
        "KCHBoard(SERIAL): User LED A is now off.",
        "KCHBoard(SERIAL): User LED A is now green.",
        "KCHBoard(SERIAL): User LED A is now cyan.",
        "KCHBoard(SERIAL): User LED C is now red.",
        "KCHBoard(SERIAL): Start LED flashing.",
        "KCHBoard(SERIAL): Start LED off.",
    ]
    with pytest.raises(ValueError, match="invalid user LED identifier 3"):
        await KCHConsoleBackend("S").get_rgb_led_channel_duty_cycle(3, RGBChannel.RED)
    with pytest.raises(ValueError, match="invalid start LED identifier 1"):
        await KCHConsoleBackend("S").get_led_mode(1)
