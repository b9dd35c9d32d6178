"""How j5aio finds the Bee Board: ``pyproject.toml``'s ``j5aio.boards`` entry point names
:func:`entries`."""

from __future__ import annotations

from j5aio.board_kinds import BoardKind, KitDefinition, SimulatorClass, SimulatorEntry

__all__ = ["entries"]


def entries() -> list[BoardKind | KitDefinition]:
    """The Bee Board, firmware 2, and a simulated kit of one beside an SR power board."""
    return [
        BoardKind(
            name="bee-fw2",
            board="beekit.boards:BeeBoard",
            description="Bee Board, firmware 2 (two motors, an LED and a button; serial)",
            # The board, backends and simulators named by import path are imported only
            # when a program uses a Bee Board, not by every j5aio program that loads the
            # plugins.
            hardware="beekit.backend:BeeBackend",
            console="beekit.console:BeeConsoleBackend",
            simulated="beekit.sim_backend:BeeSimulatedBackend",
            simulators=(
                SimulatorEntry(
                    "bee", SimulatorClass("beekit.simulator:BeeSimulator"), "Bee Board", "SIMBEE",
                    transport="serial",
                ),
            ),
            # Identify serial ports as a Bee Board only after j5aio's own boards.
            identify_order=200,
        ),
        KitDefinition("bee", "an SR v4 power board and a Bee Board", {"sr-power": 1, "bee": 1}),
    ]
