from __future__ import annotations

import pytest

from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4ServoBoardConsoleBackend,
)
from j5aio.boards.board_group import BoardGroup
from j5aio.boards.sr.v4 import MotorBoard, ServoBoard
from j5aio.components import MotorSpecialState

from .console_script import Terminal


async def test_motors_start_braked_and_print_every_change() -> None:
    terminal = Terminal()
    board = MotorBoard("SERIAL", SRV4MotorBoardConsoleBackend("SERIAL", terminal.console_class()))
    assert await board.motors[0].get_power() is MotorSpecialState.BRAKE
    assert await board.motors[1].get_power() is MotorSpecialState.BRAKE
    await board.motors[0].set_power(0.5)
    await board.motors[1].set_power(MotorSpecialState.COAST)
    await board.motors[1].set_power(-1)
    assert await board.motors[0].get_power() == 0.5
    await board.make_safe()
    assert terminal.lines == [
        "MotorBoard(SERIAL): Setting motor 0 to 0.5.",
        "MotorBoard(SERIAL): Motor 0: forward at 50% duty.",
        "MotorBoard(SERIAL): Setting motor 1 to COAST.",
        "MotorBoard(SERIAL): Setting motor 1 to -1.0.",
        "MotorBoard(SERIAL): Motor 1: reverse at 100% duty.",
        "MotorBoard(SERIAL): Setting motor 0 to BRAKE.",
        "MotorBoard(SERIAL): Setting motor 1 to BRAKE.",
    ]


async def test_motor_board_group_on_the_console() -> None:
    group = await BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)
    assert group.singular().serial_number == "SERIAL"
    assert group.singular().firmware_version is None


@pytest.mark.parametrize("identifier", [-1, 2])
async def test_unknown_motor(identifier: int) -> None:
    terminal = Terminal()
    backend = SRV4MotorBoardConsoleBackend("SERIAL", terminal.console_class())
    with pytest.raises(ValueError, match=r"invalid motor identifier .* 0 to 1"):
        await backend.set_motor_state(identifier, 0.5)
    with pytest.raises(ValueError, match="invalid motor identifier"):
        await backend.get_motor_state(identifier)
    assert terminal.lines == []


async def test_servos_start_unpowered_and_print_every_move() -> None:
    terminal = Terminal()
    board = ServoBoard("SERIAL", SRV4ServoBoardConsoleBackend("SERIAL", terminal.console_class()))
    assert [await servo.get_position() for servo in board.servos] == [None] * 12
    await board.servos[0].set_position(0.25)
    await board.servos[11].set_position(None)
    assert await board.servos[0].get_position() == 0.25
    await board.make_safe()
    assert terminal.lines == [
        "ServoBoard(SERIAL): Setting servo 0 to 0.25.",
        "ServoBoard(SERIAL): Setting servo 11 to unpowered.",
    ]


@pytest.mark.parametrize("identifier", [-1, 12])
async def test_unknown_servo(identifier: int) -> None:
    terminal = Terminal()
    backend = SRV4ServoBoardConsoleBackend("SERIAL", terminal.console_class())
    with pytest.raises(ValueError, match=r"invalid servo identifier .* 0 to 11"):
        await backend.set_servo_position(identifier, 0.5)
    with pytest.raises(ValueError, match="invalid servo identifier"):
        await backend.get_servo_position(identifier)
    assert terminal.lines == []


def test_a_console_has_no_safe_state_to_send() -> None:
    assert SRV4MotorBoardConsoleBackend("SERIAL").make_safe_now(0.5) is False
