from __future__ import annotations

import pytest

from j5aio.boards.sr.v4 import ServoBoard
from j5aio.components import Servo

from .board_fakes import FakeServoBoardBackend


def test_identity() -> None:
    board = ServoBoard("SB1", FakeServoBoardBackend())
    assert ServoBoard.name == "Student Robotics v4 Servo Board"
    assert board.serial_number == "SB1"
    assert repr(board) == "<ServoBoard serial_number='SB1'>"
    assert ServoBoard.supported_components() == {Servo}


def test_twelve_servos_read_only() -> None:
    board = ServoBoard("SB1", FakeServoBoardBackend())
    assert [servo.identifier for servo in board.servos] == list(range(12))
    with pytest.raises(TypeError):
        board.servos[0] = board.servos[1]  # type: ignore[index]
    with pytest.raises(AttributeError):
        board.servos = ()  # type: ignore[misc]


async def test_servos_reach_the_backend() -> None:
    backend = FakeServoBoardBackend()
    board = ServoBoard("SB1", backend)
    await board.servos[11].set_position(0.5)
    assert backend.servos == {11: 0.5}


async def test_make_safe_leaves_the_servos_alone() -> None:
    backend = FakeServoBoardBackend()
    board = ServoBoard("SB1", backend)
    await board.servos[3].set_position(-1.0)
    await board.make_safe()
    assert backend.named("set_servo_position") == [(3, -1.0)]
