"""ServoBoard.unpower_when_safe: make_safe switches every servo off when asked to."""

from __future__ import annotations

import pytest

from j5aio.boards.sr.v4 import ServoBoard

from .board_fakes import FakeServoBoardBackend


def test_the_servos_are_left_alone_unless_asked() -> None:
    assert ServoBoard("SB1", FakeServoBoardBackend()).unpower_when_safe is False


async def test_make_safe_switches_every_servo_off_when_asked() -> None:
    backend = FakeServoBoardBackend()
    board = ServoBoard("SB1", backend)
    await board.servos[3].set_position(-1.0)
    board.unpower_when_safe = True
    await board.make_safe()
    assert backend.named("set_servo_position") == [(3, -1.0)] + [(n, None) for n in range(12)]


def test_only_a_bool_is_taken() -> None:
    board = ServoBoard("SB1", FakeServoBoardBackend())
    with pytest.raises(TypeError, match="unpower_when_safe must be True or False, not 1"):
        board.unpower_when_safe = 1  # type: ignore[assignment]
