from __future__ import annotations

import pytest

from j5aio.boards.sr.v4 import MotorBoard
from j5aio.components import Motor, MotorSpecialState

from .board_fakes import FakeMotorBoardBackend


def test_identity() -> None:
    backend = FakeMotorBoardBackend()
    board = MotorBoard("MB1", backend)
    assert MotorBoard.name == "Student Robotics v4 Motor Board"
    assert board.serial_number == "MB1"
    assert board.firmware_version == "fake-1"
    assert repr(board) == "<MotorBoard serial_number='MB1'>"
    assert MotorBoard.supported_components() == {Motor}


def test_two_motors_read_only() -> None:
    board = MotorBoard("MB1", FakeMotorBoardBackend())
    assert [motor.identifier for motor in board.motors] == [0, 1]
    assert all(isinstance(motor, Motor) for motor in board.motors)
    with pytest.raises(TypeError):
        board.motors[0] = board.motors[1]  # type: ignore[index]
    with pytest.raises(AttributeError):
        board.motors = ()  # type: ignore[misc]


async def test_motors_reach_the_backend() -> None:
    backend = FakeMotorBoardBackend()
    board = MotorBoard("MB1", backend)
    await board.motors[1].set_power(-0.25)
    assert backend.motors == {1: -0.25}
    assert await board.motors[1].get_power() == -0.25


async def test_make_safe_brakes_by_default() -> None:
    backend = FakeMotorBoardBackend()
    board = MotorBoard("MB1", backend)
    assert board.safe_state is MotorSpecialState.BRAKE
    await board.motors[0].set_power(1.0)
    await board.make_safe()
    assert backend.motors == {0: MotorSpecialState.BRAKE, 1: MotorSpecialState.BRAKE}


@pytest.mark.parametrize("safe_state", [MotorSpecialState.COAST, 0.0, -0.5])
async def test_make_safe_uses_the_chosen_safe_state(safe_state: MotorSpecialState | float) -> None:
    backend = FakeMotorBoardBackend()
    board = MotorBoard("MB1", backend, safe_state=safe_state)
    await board.make_safe()
    assert backend.named("set_motor_state") == [(0, safe_state), (1, safe_state)]


async def test_setup_does_not_touch_the_motors() -> None:
    backend = FakeMotorBoardBackend()
    board = MotorBoard("MB1", backend)
    await board.setup()
    assert backend.calls == []


@pytest.mark.parametrize("safe_state", [1.5, -2, float("nan")])
def test_safe_state_out_of_range(safe_state: float) -> None:
    with pytest.raises(ValueError, match="safe_state"):
        MotorBoard("MB1", FakeMotorBoardBackend(), safe_state=safe_state)


@pytest.mark.parametrize("safe_state", ["BRAKE", True, None])
def test_safe_state_wrong_type(safe_state: object) -> None:
    with pytest.raises(TypeError, match="safe_state"):
        MotorBoard("MB1", FakeMotorBoardBackend(), safe_state=safe_state)  # type: ignore[arg-type]
