"""The project's own tests using the pytest plugin's fixtures on real robot code paths."""

from __future__ import annotations

import anyio
import pytest

from j5aio.backends.hardware.sr.v4 import SRV4MotorBoardHardwareBackend
from j5aio.boards.board import Board
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.boards.sr.v4.power_board import PowerBoard, PowerOutputPosition
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import CommunicationError
from j5aio.simulator.sr_motor_fw3 import MotorMode
from j5aio.testing import Fault, OpenSimulatedKit
from j5aio.testing.plugin import FaultyStreamFactory, PtySimulatorFactory


async def test_make_all_safe_stops_the_simulated_motors(j5aio_sim_kit: OpenSimulatedKit) -> None:
    for board in j5aio_sim_kit.group(MotorBoard):
        for motor in board.motors:
            await motor.set_power(0.75)
    assert not await Board.make_all_safe()
    for simulator in j5aio_sim_kit.kit.motor_boards:
        assert [output.mode for output in simulator.motors] == [MotorMode.BRAKE] * 2


async def test_power_outputs_and_start_button_on_the_kit(
    j5aio_sim_kit: OpenSimulatedKit,
) -> None:
    power_board = j5aio_sim_kit.group(PowerBoard).singular()
    simulator = j5aio_sim_kit.kit.power_boards[0]
    await power_board.outputs[PowerOutputPosition.H0].set_is_enabled(True)
    assert simulator.outputs[PowerOutputPosition.H0.value]
    await power_board.outputs.power_off()
    assert not any(simulator.outputs)
    with anyio.move_on_after(0.2) as scope:
        await power_board.start_button.wait_until_pressed()
    assert scope.cancelled_caught
    simulator.press_start()
    await power_board.start_button.wait_until_pressed(timeout=2)


@pytest.mark.j5aio_kit(power_boards=0, servo_boards=0, sb_arduinos=0, motor_boards=1)
async def test_a_motor_board_that_stops_answering(
    j5aio_pty_simulator: PtySimulatorFactory, j5aio_faulty_stream: FaultyStreamFactory,
    j5aio_sim_kit: OpenSimulatedKit,
) -> None:
    from j5aio.backends.hardware.transports.serial_stream import open_serial_stream

    path = j5aio_pty_simulator("sr-motor")
    stream = j5aio_faulty_stream(
        await open_serial_stream(path, baudrate=SRV4MotorBoardHardwareBackend.BAUDRATE),
    )
    board = await SRV4MotorBoardHardwareBackend.from_stream(
        stream, port=path, serial_number="PTY0", time_scale=0,
    )
    assert isinstance(board, MotorBoard)
    try:
        await board.motors[0].set_power(MotorSpecialState.COAST)
        stream.inject(Fault.disconnect())
        with pytest.raises(CommunicationError):
            await board.motors[0].set_power(0.5)
    finally:
        await board.close()
    assert len(j5aio_sim_kit.kit) == 1
