"""The hardware environment: the backends that find and drive each kind of real board.

Its backends are the hardware backends of the registered board kinds
(:func:`j5aio.board_kinds.board_kinds`): j5aio's own and those of installed plugins.
"""

from __future__ import annotations

from j5aio.backends.backend import Backend
from j5aio.backends.environment import Environment
from j5aio.board_kinds import board_kinds

__all__ = ["HARDWARE_BACKENDS", "HARDWARE_ENVIRONMENT"]

#: Every hardware backend, in the order listing tries them (the registry's order). The
#: SourceBots Arduino comes before the Ruggeduino: both use the same USB IDs.
HARDWARE_BACKENDS: tuple[type[Backend], ...] = tuple(
    kind.hardware for kind in board_kinds() if kind.hardware is not None
)

#: Real boards: SR v4 power (fw 3), motor (fw 3), servo (fw 2) boards and Ruggeduino
#: (fw 1), the SourceBots Arduino (2019 protocol), and every plugin's boards.
HARDWARE_ENVIRONMENT = Environment.from_backends("HardwareEnvironment", HARDWARE_BACKENDS)
