from __future__ import annotations

from collections.abc import Iterator

import pytest

from j5aio.backends.console import CONSOLE_ENVIRONMENT, ConsoleBackend
from j5aio.backends.console.sb import SBArduino2024ConsoleBackend, SBArduinoConsoleBackend
from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SBServoBoardConsoleBackend,
    SRArduinoConsoleBackend,
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
    SRV4ServoBoardFw4ConsoleBackend,
)
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduino2024Board, SBArduinoBoard, SBServoBoard
from j5aio.boards.sr.kch import KCHBoard
from j5aio.boards.sr.v4 import (
    MotorBoard,
    PowerBoard,
    Ruggeduino,
    ServoBoard,
    ServoBoardFw4,
    SRArduinoBoard,
)

from .console_script import Terminal

BACKENDS: dict[type[Board], type[ConsoleBackend]] = {
    PowerBoard: SRV4PowerBoardConsoleBackend,
    MotorBoard: SRV4MotorBoardConsoleBackend,
    ServoBoard: SRV4ServoBoardConsoleBackend,
    Ruggeduino: SRV4RuggeduinoConsoleBackend,
    SBArduinoBoard: SBArduinoConsoleBackend,
    ServoBoardFw4: SRV4ServoBoardFw4ConsoleBackend,
    SBServoBoard: SBServoBoardConsoleBackend,
    KCHBoard: KCHConsoleBackend,
    SRArduinoBoard: SRArduinoConsoleBackend,
    SBArduino2024Board: SBArduino2024ConsoleBackend,
}


def test_every_console_backend_is_registered() -> None:
    assert CONSOLE_ENVIRONMENT.name == "ConsoleEnvironment"
    assert CONSOLE_ENVIRONMENT.supported_boards >= set(BACKENDS)  # and plugins' boards
    for board, backend in BACKENDS.items():
        assert CONSOLE_ENVIRONMENT.get_backend(board) is backend


@pytest.fixture
def terminal() -> Iterator[Terminal]:
    terminal = Terminal()
    saved = ConsoleBackend.console_class
    ConsoleBackend.console_class = terminal.console_class()
    try:
        yield terminal
    finally:
        ConsoleBackend.console_class = saved


@pytest.mark.parametrize("board_type", list(BACKENDS))
async def test_each_board_is_found_and_set_up(board_type: type[Board], terminal: Terminal) -> None:
    group = await CONSOLE_ENVIRONMENT.get_board_group(board_type)
    board = group.singular()
    assert type(board) is board_type
    assert board.serial_number == "SERIAL"
    assert board.firmware_version is None
    assert board in Board.BOARDS
    await board.make_safe()
    await board.close()
    assert board not in Board.BOARDS


async def test_the_uno_boards_print_their_pin_modes_on_setup(terminal: Terminal) -> None:
    await CONSOLE_ENVIRONMENT.get_board_group(SBArduinoBoard)
    assert terminal.lines[0] == "SBArduinoBoard(SERIAL): Set pin 2 to DIGITAL_INPUT"
    assert len(terminal.lines) == 18
