"""How j5aio finds the Blinken board: the entry point ``j5aio.boards`` names :func:`entries`."""

from __future__ import annotations

from j5aio.board_kinds import BoardKind, KitDefinition, SimulatorEntry
from j5aio_blinken.backend import BlinkenHardwareBackend
from j5aio_blinken.board import BlinkenBoard
from j5aio_blinken.console import BlinkenConsoleBackend
from j5aio_blinken.simulator import BlinkenSimulator

__all__ = ["entries"]


def entries() -> list[BoardKind | KitDefinition]:
    """The Blinken board kind, and a simulated kit with one beside an SR power board."""
    return [
        BoardKind(
            name="blinken-v1",
            board=BlinkenBoard,
            description="Blinken board, firmware 1 (four LEDs, serial)",
            hardware=BlinkenHardwareBackend,
            console=BlinkenConsoleBackend,
            simulators=(
                SimulatorEntry("blinken", BlinkenSimulator, "Blinken board (four LEDs)", "SIMBL"),
            ),
            identify_order=200,
        ),
        KitDefinition(
            "blinken",
            "an SR v4 power board and a Blinken board",
            {"sr-power": 1, "blinken": 1},
        ),
    ]
