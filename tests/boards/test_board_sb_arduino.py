from __future__ import annotations

from datetime import timedelta

import pytest

from j5aio.boards.arduino import AnaloguePin, ArduinoUno
from j5aio.boards.sb import SBArduinoBoard, UltrasoundSensors
from j5aio.components import LED, GPIOPin, Servo, UltrasoundSensor
from j5aio.errors import NotSupportedByComponentError

from .board_fakes import FakeSBArduinoBackend


def make_board() -> tuple[SBArduinoBoard, FakeSBArduinoBackend]:
    backend = FakeSBArduinoBackend()
    return SBArduinoBoard("SB1", backend), backend


def test_identity() -> None:
    board, _ = make_board()
    assert isinstance(board, ArduinoUno)
    assert SBArduinoBoard.name == "SourceBots Arduino"
    assert repr(board) == "<SBArduinoBoard serial_number='SB1'>"
    assert SBArduinoBoard.supported_components() == {GPIOPin, LED, Servo, UltrasoundSensor}


def test_digital_pins_allow_ultrasound_analogue_pins_do_not() -> None:
    board, _ = make_board()
    for number in range(2, 14):
        assert board.pins[number].firmware_modes == frozenset({UltrasoundSensor})
    for pin in AnaloguePin:
        assert board.pins[pin].firmware_modes == frozenset()


def test_sixteen_servos() -> None:
    board, _ = make_board()
    assert [servo.identifier for servo in board.servos] == list(range(16))
    with pytest.raises(AttributeError):
        board.servos = ()  # type: ignore[misc]


async def test_ultrasound_sensor_on_a_pin_pair() -> None:
    board, backend = make_board()
    assert isinstance(board.ultrasound_sensors, UltrasoundSensors)
    sensor = board.ultrasound_sensors[4, 5]
    assert isinstance(sensor, UltrasoundSensor)
    assert await sensor.distance() == 0.1
    assert await sensor.pulse() == timedelta(microseconds=580)
    assert backend.named("get_ultrasound_distance") == [(4, 5)]
    assert backend.named("get_ultrasound_pulse") == [(4, 5)]
    assert "SBArduinoBoard" in repr(board.ultrasound_sensors)
    with pytest.raises(AttributeError):
        board.ultrasound_sensors = board.ultrasound_sensors  # type: ignore[misc]


def test_ultrasound_on_analogue_pins_is_refused() -> None:
    board, _ = make_board()
    with pytest.raises(NotSupportedByComponentError):
        board.ultrasound_sensors[AnaloguePin.A0, 5]


@pytest.mark.parametrize("pins", [(0, 5), (4, 20), (1, 99)])
def test_ultrasound_on_missing_pins(pins: tuple[int, int]) -> None:
    board, _ = make_board()
    with pytest.raises(KeyError, match="pins are 2 to 19"):
        board.ultrasound_sensors[pins]


@pytest.mark.parametrize("pins", [4, (4,), (4, 5, 6), "45", [4, 5]])
def test_ultrasound_needs_a_pair(pins: object) -> None:
    board, _ = make_board()
    with pytest.raises(TypeError, match="pair of pin numbers"):
        board.ultrasound_sensors[pins]  # type: ignore[index]


@pytest.mark.parametrize("pins", [("4", 5), (4, 5.0), (True, 5)])
def test_ultrasound_pins_must_be_ints(pins: tuple[object, object]) -> None:
    board, _ = make_board()
    with pytest.raises(TypeError, match="pin number must be an int"):
        board.ultrasound_sensors[pins]  # type: ignore[index]
