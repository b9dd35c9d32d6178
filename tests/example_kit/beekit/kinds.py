"""How j5aio finds the Bee Board: ``pyproject.toml``'s ``j5aio.boards`` entry point names
:func:`entries`."""

from __future__ import annotations

from j5aio.board_kinds import BoardKind, KitDefinition, SimulatorEntry

from .backend import BeeBackend
from .boards import BeeBoard
from .console import BeeConsoleBackend
from .simulator import BeeSimulator

__all__ = ["entries"]


def entries() -> list[BoardKind | KitDefinition]:
    """The Bee Board, firmware 2, and a simulated kit of one beside an SR power board."""
    return [
        BoardKind(
            name="bee-fw2",
            board=BeeBoard,
            description="Bee Board, firmware 2 (two motors, an LED and a button; serial)",
            hardware=BeeBackend,
            console=BeeConsoleBackend,
            simulators=(SimulatorEntry("bee", BeeSimulator, "Bee Board", "SIMBEE"),),
            # Identify serial ports as a Bee Board only after j5aio's own boards.
            identify_order=200,
        ),
        KitDefinition("bee", "an SR v4 power board and a Bee Board", {"sr-power": 1, "bee": 1}),
    ]
