"""A board's numbered components: a tuple whose misses name the board and its numbers."""

from __future__ import annotations

import pytest

from j5aio.boards.sr.v4 import MotorBoard
from j5aio.numbered import NoSuchComponentError, NumberedComponents

from .board_fakes import FakeMotorBoardBackend


def test_a_missing_motor_names_the_board_and_its_motors() -> None:
    board = MotorBoard("MB1", FakeMotorBoardBackend())
    with pytest.raises(IndexError, match=r"MB1 has motors 0 to 1: there is no motor 2"):
        board.motors[2]
    with pytest.raises(NoSuchComponentError):
        board.motors[-3]


def test_it_is_still_a_tuple() -> None:
    board = MotorBoard("MB1", FakeMotorBoardBackend())
    left, right = board.motors
    assert board.motors == (left, right)
    assert board.motors[-1] is right
    assert board.motors[0:1] == (left,)
    assert len(board.motors) == 2
    assert isinstance(board.motors, tuple)


def test_a_word_is_no_number() -> None:
    board = MotorBoard("MB1", FakeMotorBoardBackend())
    with pytest.raises(TypeError, match="motors are numbered: use a whole number from 0 to 1"):
        board.motors["left"]  # type: ignore[call-overload]


def test_an_empty_set_says_so() -> None:
    empty: NumberedComponents[int] = NumberedComponents((), owner="board X", kind="LED")
    with pytest.raises(NoSuchComponentError, match="board X has no LEDs: there is no LED 0"):
        empty[0]


def test_the_facade_keeps_the_numbering_around_its_wrappers() -> None:
    numbered = NumberedComponents([1, 2], owner="B", kind="servo")
    replaced: NumberedComponents[str] = numbered.replaced(["a", "b"])
    with pytest.raises(NoSuchComponentError, match="B has servos 0 to 1: there is no servo 5"):
        replaced[5]
    assert replaced == ("a", "b")
