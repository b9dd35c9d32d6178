"""On the firmware 3 motor board, the duty driven is the power given."""

import pytest

from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardHardwareBackend,
    SRV4MotorBoardJ5ScaleHardwareBackend,
)
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.simulator import MotorMode, SRMotorBoardFw3Simulator


async def connect(
    backend: type[SRV4MotorBoardHardwareBackend], sim: SRMotorBoardFw3Simulator,
) -> Board:
    stream = SimulatorStream(sim, time_scale=0)
    board = await backend.from_stream(stream, port="sim", serial_number="SR0M")
    await board.setup()
    return board


@pytest.mark.parametrize("power", [0.5, 0.8, 0.9, 1.0, -0.5, -0.8, -0.9, -1.0, 0.33])
async def test_simulated_duty_matches_the_power(power: float) -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board = await connect(SRV4MotorBoardHardwareBackend, sim)
    assert isinstance(board, MotorBoard)
    await board.motors[0].set_power(power)
    output = sim.motors[0]
    assert output.mode is (MotorMode.FORWARD if power > 0 else MotorMode.REVERSE)
    assert output.duty == pytest.approx(abs(power))
    assert output.power == pytest.approx(power)
    await board.close()


async def test_0_9_and_1_0_differ_on_the_board() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board = await connect(SRV4MotorBoardHardwareBackend, sim)
    assert isinstance(board, MotorBoard)
    await board.motors[0].set_power(0.9)
    await board.motors[1].set_power(1.0)
    assert sim.motors[0].duty < sim.motors[1].duty
    await board.close()


@pytest.mark.parametrize(
    ("power", "duty"), [(0.5, 0.62), (0.6, 0.75), (0.8, 1.0), (0.9, 1.0), (1.0, 1.0)],
)
async def test_j5_scale_is_an_opt_in_with_j5s_duty(power: float, duty: float) -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board = await connect(SRV4MotorBoardJ5ScaleHardwareBackend, sim)
    assert isinstance(board, MotorBoard)
    await board.motors[1].set_power(power)
    assert sim.motors[1].duty == pytest.approx(duty)
    assert await board.motors[1].get_power() == power
    await board.close()
