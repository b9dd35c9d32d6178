"""An imaginary board kind to register in tests of the board kind registry."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.board_kinds import BoardKind, SimulatorEntry
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.simulator.discovery import kind_options
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator


class MotorBoardGen9(MotorBoard):
    """An imaginary later motor board generation, to register."""

    name = "Motor Board gen 9"


class Gen9HardwareBackend(SRV4MotorBoardHardwareBackend):
    """Its backend (the fw 3 protocol, for the test)."""

    board = MotorBoardGen9


class Gen9SimulatedBackend(Gen9HardwareBackend):
    """Its simulated backend: the hardware one, finding the simulated kit's gen 9 boards."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's gen 9 boards."""
        return await super().discover(options=options or kind_options(cls))


GEN9 = BoardKind(
    name="test-motor-gen9",
    board=MotorBoardGen9,
    description="a test motor board",
    hardware=Gen9HardwareBackend,
    simulated=Gen9SimulatedBackend,
    simulators=(
        SimulatorEntry(
            "test-motor-gen9", SRMotorBoardFw3Simulator, "test motor", "SIMG9", {"sr2019": 2},
            transport="serial",
        ),
    ),
)
