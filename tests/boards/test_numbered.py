"""A board's numbered components: a tuple whose misses name the board and its numbers."""

from __future__ import annotations

import pytest

from j5aio.boards.arduino import AnaloguePin, ArduinoUno
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.components import GPIOPin
from j5aio.numbered import NoSuchComponentError, NoSuchPinError, NumberedComponents

from .board_fakes import FakeMotorBoardBackend, FakeUnoBackend


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


def test_iterating_the_pins_gives_pins_as_in_j5() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    pins = list(board.pins)
    assert all(isinstance(pin, GPIOPin) for pin in pins)
    assert [pin.identifier for pin in pins] == list(range(2, 20))
    assert list(board.pins.keys()) == list(range(2, 20))
    assert list(board.pins.values()) == pins
    assert dict(board.pins.items())[14] is board.pins[AnaloguePin.A0]
    assert len(board.pins) == 18
    assert 14 in board.pins and 0 not in board.pins and "3" not in board.pins
    assert [3] not in board.pins  # unhashable: simply not a pin number
    assert board.pins.get(0) is None and board.pins.get(2) is pins[0]
    assert repr(board.pins).startswith("<pins 2, 3, 4,")


def test_a_missing_pin_names_the_board_and_its_pins() -> None:
    board = ArduinoUno("U1", FakeUnoBackend())
    with pytest.raises(KeyError) as caught:
        board.pins[0]
    assert isinstance(caught.value, NoSuchPinError)
    assert str(caught.value) == "Arduino Uno - U1 has no pin 0; its pins are 2 to 19"
    with pytest.raises(TypeError, match="pins are numbered: use a whole number, not list"):
        board.pins[[3]]  # type: ignore[index]
