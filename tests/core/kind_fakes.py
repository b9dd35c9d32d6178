"""An imaginary board kind to register in tests of the board kind registry."""

from __future__ import annotations

from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.board_kinds import BoardKind, SimulatorEntry
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator


class MotorBoardGen9(MotorBoard):
    """An imaginary later motor board generation, to register."""

    name = "Motor Board gen 9"


class Gen9HardwareBackend(SRV4MotorBoardHardwareBackend):
    """Its backend (the fw 3 protocol, for the test)."""

    board = MotorBoardGen9


GEN9 = BoardKind(
    name="test-motor-gen9",
    board=MotorBoardGen9,
    description="a test motor board",
    hardware=Gen9HardwareBackend,
    simulators=(
        SimulatorEntry(
            "test-motor-gen9", SRMotorBoardFw3Simulator, "test motor", "SIMG9", {"sr2019": 2}
        ),
    ),
)
