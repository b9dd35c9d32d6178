"""The fw 4 power and motor backends attach to their simulators served on pseudo-terminals."""

import sys

import pytest

from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardFw4HardwareBackend,
    SRV4PowerBoardFw4HardwareBackend,
)
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, PowerBoardOutput
from j5aio.simulator import SERIAL_SIMULATORS, MotorDrive
from j5aio.simulator.serve import serve_on_pty

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="needs pseudo-terminals")


async def test_power_board_fw4_on_a_pty() -> None:
    sim = SERIAL_SIMULATORS["sr-power-fw4"]("srPTY")
    async with serve_on_pty(sim, time_scale=0) as server:
        board = await SRV4PowerBoardFw4HardwareBackend.attach(server.path)
        assert isinstance(board, PowerBoardFw4)
        await board.setup()
        assert board.firmware_version == "4.4.2"
        await board.outputs[PowerBoardOutput.H1].set_is_enabled(True)
        assert await board.outputs[PowerBoardOutput.H1].get_is_enabled() is True
        await board.make_safe()
        await board.close()


async def test_motor_board_fw4_on_a_pty() -> None:
    sim = SERIAL_SIMULATORS["sr-motor-fw4"]("srPTY")
    async with serve_on_pty(sim, time_scale=0) as server:
        board = await SRV4MotorBoardFw4HardwareBackend.attach(server.path)
        assert isinstance(board, MotorBoardFw4)
        await board.setup()
        await board.motors[0].set_power(-0.4)
        assert await board.motors[0].get_power() == -0.4
        await board.make_safe()
        await board.close()
    assert [m.drive for m in sim.motors] == [MotorDrive.BRAKE, MotorDrive.BRAKE]  # type: ignore[attr-defined]
