"""Constructors, static and class methods of the wrappers, and other boards' wrappers."""

from __future__ import annotations

import inspect
import logging

import pytest

from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
)
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.components.piezo import Note
from j5aio.sync import _generated as sync
from j5aio.sync import _runtime, wrapping
from j5aio.sync._runtime import call
from j5aio.sync.wrapping import _WRAPPER_CLASSES, wrap

from .sync_fakes import ScriptedConsoleLog


def power_of(motor: sync.Motor) -> MotorState:
    return motor.power


def registered() -> list[tuple[type, type]]:
    wrapping.registered()  # (registers the classes registered by name, too)
    return [(core, wrapper) for core, wrapper in _WRAPPER_CLASSES.items() if wrapper is not None]


@pytest.mark.parametrize("method", ["supported_components", "interface_class"])
def test_static_and_class_methods_answer_as_the_core_does(method: str) -> None:
    checked = 0
    for core, wrapper in registered():
        if method not in vars(wrapper) or inspect.isabstract(core):
            continue
        assert getattr(wrapper, method)() == getattr(core, method)()
        checked += 1
    assert checked >= 5


def test_piezo_checks_are_forwarded() -> None:
    sync.Piezo.verify_pitch(Note.A6)
    with pytest.raises(ValueError):
        sync.Piezo.verify_pitch(-1)
    with pytest.raises((TypeError, ValueError)):
        sync.Piezo.verify_duration(-1)  # type: ignore[arg-type]


def test_make_all_safe_reaches_every_board() -> None:
    log = ScriptedConsoleLog()
    board = sync.MotorBoard("MB9", SRV4MotorBoardConsoleBackend("MB9", log.console_class()))
    board.setup()
    board.motors[0].power = 0.5
    assert sync.Board.make_all_safe() == []
    assert power_of(board.motors[0]) is MotorSpecialState.BRAKE
    board.close()


def test_boards_can_be_built_in_sync_code() -> None:
    log = ScriptedConsoleLog()
    console = log.console_class()
    motor = sync.MotorBoard("M", SRV4MotorBoardConsoleBackend("M", console), safe_state=0.0)
    assert wrap(motor._core) is motor
    assert motor.safe_state == 0.0
    power = sync.PowerBoard("P", SRV4PowerBoardConsoleBackend("P", console))
    servo = sync.ServoBoard("S", SRV4ServoBoardConsoleBackend("S", console))
    ruggeduino = sync.Ruggeduino("R", SRV4RuggeduinoConsoleBackend("R", console))
    for board in (motor, power, servo, ruggeduino):
        board.setup()
        assert isinstance(board, sync.Board)
    servo.servos[3].position = 0.5
    assert servo.servos[3].position == 0.5
    assert ruggeduino.pins[13] is ruggeduino.pins[13]
    assert isinstance(ruggeduino.pins[13], sync.GPIOPin)


def test_arduino_boards_pins_servos_and_ultrasound() -> None:
    log = ScriptedConsoleLog()
    backend = SBArduinoConsoleBackend("A", log.console_class())
    board = sync.SBArduinoBoard("A", backend)
    board.setup()
    uno = sync.ArduinoUno("U", SBArduinoConsoleBackend("U", log.console_class()))
    assert isinstance(uno, sync.ArduinoUno)
    pin = board.pins[3]
    pin.mode = GPIOPinMode.DIGITAL_OUTPUT
    pin.digital_write(True)
    assert pin.last_digital_write is True
    assert GPIOPinMode.DIGITAL_OUTPUT in pin.hardware_modes
    assert int(board.AnaloguePin.A0) == 14
    board.servos[0].position = -0.5
    sensor = board.ultrasound_sensors[4, 5]
    assert isinstance(sensor, sync.UltrasoundSensor)
    built = sync.UltrasoundSensor(board.pins[6], board.pins[7], backend)
    assert isinstance(built, sync.UltrasoundSensor)
    sensors = sync.UltrasoundSensors(board)
    assert isinstance(sensors[8, 9], sync.UltrasoundSensor)
    own_pin = sync.GPIOPin(20, backend, initial_mode=GPIOPinMode.DIGITAL_OUTPUT)
    assert own_pin.identifier == 20


def test_power_output_group_from_sync_outputs() -> None:
    log = ScriptedConsoleLog()
    power = sync.PowerBoard("P", SRV4PowerBoardConsoleBackend("P", log.console_class()))
    outputs = list(power.outputs)
    group = sync.PowerOutputGroup({"front": outputs[0], "back": outputs[1]})
    assert group["front"] is outputs[0]
    group.power_on()
    assert [o.is_enabled for o in outputs[:3]] == [True, True, False]


def test_shutdown_logs_a_board_that_cannot_close(caplog: pytest.LogCaptureFixture) -> None:
    class BrokenCloseBackend(SRV4MotorBoardConsoleBackend):
        async def close(self) -> None:
            raise OSError("port vanished")

    log = ScriptedConsoleLog()
    board = sync.MotorBoard("X", BrokenCloseBackend("X", log.console_class()))
    board.setup()
    board.motors[0].power = 0.5
    with caplog.at_level(logging.ERROR):
        _runtime.shutdown()
    assert "Could not close" in caplog.text
    assert "port vanished" in caplog.text
    assert log.printed[-2:] == [
        "MotorBoard(X): Setting motor 0 to BRAKE.",
        "MotorBoard(X): Setting motor 1 to BRAKE.",
    ]
    assert call(board._core.make_safe) is None  # a new portal starts
