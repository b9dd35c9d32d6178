"""The generated wrappers on console boards: properties, methods, identity, slots, groups."""

from __future__ import annotations

import inspect

import pytest

from j5aio import sync
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
)
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.boards.sr.v4.power_board import PowerOutputPosition
from j5aio.components.motor import Motor as CoreMotor
from j5aio.components.motor import MotorSpecialState
from j5aio.components.power_output import PowerOutput as CorePowerOutput
from j5aio.errors import CommunicationError, UnableToObtainLock

from .sync_fakes import ScriptedConsoleLog, motor_board, power_board


def test_get_set_pair_is_a_read_write_property() -> None:
    log = ScriptedConsoleLog()
    board = power_board(log)
    output = board.outputs[PowerOutputPosition.L1]
    output.is_enabled = True
    assert output.is_enabled is True
    assert log.printed[-1] == "PowerBoard(PB1): Setting output 3 to True"
    output.is_enabled = False
    assert output.is_enabled is False


def test_lone_getter_is_a_read_only_property() -> None:
    log = ScriptedConsoleLog(["1.5", "12.25"])
    board = power_board(log)
    assert board.outputs[PowerOutputPosition.H0].current == 1.5
    assert board.battery_sensor.voltage == 12.25
    with pytest.raises(AttributeError):
        board.battery_sensor.voltage = 3.0  # type: ignore[misc]


def test_other_coroutines_are_blocking_methods() -> None:
    log = ScriptedConsoleLog()
    board = power_board(log)
    board.piezo.buzz(0.25, 440)
    assert log.printed[-1].startswith("PowerBoard(PB1): Buzzing at 440")
    assert log.printed[-1].endswith("Hz for 250ms")
    board.outputs.power_on()
    assert all(output.is_enabled for output in board.outputs)
    board.make_safe()
    assert not any(output.is_enabled for output in board.outputs)


def test_core_errors_reach_the_caller_unchanged() -> None:
    board = motor_board(ScriptedConsoleLog())
    with pytest.raises(ValueError, match="motor power"):
        board.motors[0].power = 1.5
    with pytest.raises(TypeError):
        board.motors[0].power = "fast"  # type: ignore[assignment]
    assert board.motors[0].power is MotorSpecialState.BRAKE


def test_misspelt_attribute_is_refused() -> None:
    board = power_board(ScriptedConsoleLog())
    output = board.outputs[PowerOutputPosition.H0]
    with pytest.raises(AttributeError):
        output.is_enabeld = True  # type: ignore[attr-defined]
    with pytest.raises(AttributeError):
        board.motors = ()  # type: ignore[attr-defined]


def test_wrappers_are_cached_so_identity_holds() -> None:
    log = ScriptedConsoleLog()
    motors = motor_board(log)
    assert motors.motors[0] is motors.motors[0]
    assert motors.motors[0] is not motors.motors[1]
    power = power_board(log)
    assert power.outputs is power.outputs
    assert power.outputs[PowerOutputPosition.H1] is power.outputs[PowerOutputPosition.H1]
    assert list(power.outputs)[1] is power.outputs[PowerOutputPosition.H1]
    assert power.piezo is power.piezo


def test_wrappers_are_the_sync_classes_and_hold_their_core_object() -> None:
    board = motor_board(ScriptedConsoleLog())
    motor = board.motors[0]
    assert isinstance(motor, sync.Motor)
    assert isinstance(motor, sync.Component)
    assert isinstance(motor._core, CoreMotor)
    assert isinstance(board.motors, tuple)
    assert str(board) == "Student Robotics v4 Motor Board - MB1"
    assert "Motor" in repr(motor)


def test_plain_attributes_stay_plain() -> None:
    board = power_board(ScriptedConsoleLog())
    assert board.serial_number == "PB1"
    assert board.firmware_version is None
    assert board.name == PowerBoard.name == sync.PowerBoard.name
    assert board.outputs[PowerOutputPosition.L3].identifier == 5
    assert len(board.outputs) == 6
    assert CorePowerOutput in board.supported_components()


def test_docstrings_are_carried_over() -> None:
    sync_doc = inspect.getdoc(sync.PowerOutput.is_enabled)
    core_doc = inspect.getdoc(CorePowerOutput.get_is_enabled)
    assert sync_doc is not None
    assert core_doc is not None
    assert sync_doc.startswith(core_doc)
    assert inspect.getdoc(sync.Motor) == inspect.getdoc(CoreMotor)
    assert inspect.getdoc(sync.PowerBoard.wait_for_start_flash) == inspect.getdoc(
        PowerBoard.wait_for_start_flash,
    )


def test_board_group_holds_sync_boards(capsys: pytest.CaptureFixture[str]) -> None:
    group = sync.BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)
    assert isinstance(group, sync.BoardGroup)
    assert len(group) == 1
    board = group.singular()
    assert isinstance(board, sync.MotorBoard)
    assert group[0] is board
    assert group[board.serial_number] is board
    assert board.serial_number in group
    assert list(group) == [board]
    assert group.boards == [board]
    assert group.board_type is MotorBoard
    assert group.backend_class is SRV4MotorBoardConsoleBackend
    board.motors[1].power = -0.25
    group.make_safe()
    printed = capsys.readouterr().out
    assert "MotorBoard(SERIAL): Setting motor 1 to -0.25." in printed
    assert printed.rstrip().endswith("Setting motor 1 to BRAKE.")


def test_board_group_errors_are_the_cores() -> None:
    group = sync.BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend)
    with pytest.raises(KeyError, match="NOPE"):
        group["NOPE"]
    with pytest.raises(IndexError):
        group[3]
    empty = sync.BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend)
    empty._core._boards.clear()
    with pytest.raises(CommunicationError, match="exactly one"):
        empty.singular()


def test_board_group_takes_the_sync_board_classes_too() -> None:
    group = sync.BoardGroup.get_board_group(sync.MotorBoard, SRV4MotorBoardConsoleBackend)
    assert isinstance(group.singular(), sync.MotorBoard)
    assert group.board_type is MotorBoard
    env_group = sync.CONSOLE_ENVIRONMENT.get_board_group(sync.PowerBoard)
    assert isinstance(env_group.singular(), sync.PowerBoard)
    assert sync.CONSOLE_ENVIRONMENT.get_backend(sync.PowerBoard) is SRV4PowerBoardConsoleBackend


def test_a_sync_board_class_of_the_wrong_kind_is_still_refused() -> None:
    with pytest.raises(TypeError, match="drives MotorBoard, not PowerBoard"):
        sync.BoardGroup.get_board_group(sync.PowerBoard, SRV4MotorBoardConsoleBackend)


def test_environment_objects_are_wrapped() -> None:
    env = sync.CONSOLE_ENVIRONMENT
    assert isinstance(env, sync.Environment)
    assert env.get_backend(PowerBoard) is SRV4PowerBoardConsoleBackend
    group = env.get_board_group(PowerBoard)
    assert isinstance(group.singular(), sync.PowerBoard)
    assert PowerBoard in env.supported_boards
    assert env.name == "ConsoleEnvironment"


def test_environment_can_be_built_and_merged_in_sync_code() -> None:
    first = sync.Environment("First")
    first.register_backend(SRV4PowerBoardConsoleBackend)
    second = sync.Environment("Second")
    second.register_backend(SRV4MotorBoardConsoleBackend)
    first.merge(second)
    assert first.supported_boards == {PowerBoard, MotorBoard}
    assert first.board_backend_mapping[MotorBoard] is SRV4MotorBoardConsoleBackend
    with pytest.raises(RuntimeError, match="both have a backend"):
        first.merge(second)


def test_base_robot_takes_the_lock_without_super_init() -> None:
    class MyRobot(sync.BaseRobot):
        def __init__(self) -> None:
            self.motors = sync.BoardGroup.get_board_group(
                MotorBoard, SRV4MotorBoardConsoleBackend,
            ).singular()

    robot = MyRobot()
    try:
        assert isinstance(robot.motors, sync.MotorBoard)
        with pytest.raises(UnableToObtainLock):
            MyRobot()
        assert robot.motors in robot.boards()
        robot.motors.motors[0].power = 0.5
        robot.make_safe()
        assert robot.boards() == {robot.motors}
        assert robot.motors.motors[1].power is MotorSpecialState.BRAKE
    finally:
        robot.release_lock()
    second = MyRobot()
    second.release_lock()


def test_sync_package_exports_what_j5_does() -> None:
    for name in ("BaseRobot", "BoardGroup", "Environment", "Board", "shutdown", "__version__"):
        assert name in sync.__all__
        assert hasattr(sync, name)


def test_environment_functions_return_the_sync_environments(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    assert sync.get_environment("console") is sync.CONSOLE_ENVIRONMENT
    assert sync.console_environment() is sync.CONSOLE_ENVIRONMENT
    assert sync.hardware_environment() is sync.HARDWARE_ENVIRONMENT
    assert isinstance(sync.simulated_environment(), sync.Environment)
    monkeypatch.setenv("J5AIO_ENV", "console")
    assert sync.get_default_environment() is sync.CONSOLE_ENVIRONMENT
    with pytest.raises(ValueError, match="choose one of"):
        sync.get_environment("moon")
