"""The simulated backends of the SR v4 boards of firmware 3 (and 2) and the 2019 Arduinos.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` made from its kind's simulators (see
:mod:`j5aio.simulator.discovery`), and nothing else: from there on every call runs the
hardware backend's own code (its polls included) over a simulated transport, as on a
robot. Each board kind names its simulated backend (``simulated=`` of
:class:`~j5aio.board_kinds.BoardKind`); the simulated environment imports this module the
first time it needs one of them. The power, motor and servo boards' are in every kit of
these boards; each Arduino's is imported, with its hardware backend, the first time it is
looked up here, so that a kit imports the backend of the Arduino it has only. The later
boards' are in :mod:`j5aio.simulator.sim_backends_2023`.

A plugin's simulated backend is written the same way, with
:class:`~j5aio.simulator.discovery.KitDiscovery` first among its bases::

    class BeeSimulatedBackend(KitDiscovery, BeeBackend):
        "The Bee Board's backend, on the simulated kit."
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend

from .discovery import KitDiscovery

if TYPE_CHECKING:
    from ._sim_sb_arduino_2019 import SBArduinoSimulatedBackend as SBArduinoSimulatedBackend
    from ._sim_sr_ruggeduino_fw1 import (
        SRV4RuggeduinoSimulatedBackend as SRV4RuggeduinoSimulatedBackend,
    )


class SRV4PowerBoardSimulatedBackend(KitDiscovery, SRV4PowerBoardHardwareBackend):
    """The SR v4 power board (firmware 3) hardware backend, on the simulated kit."""


class SRV4MotorBoardSimulatedBackend(KitDiscovery, SRV4MotorBoardHardwareBackend):
    """The SR v4 motor board (firmware 3) hardware backend, on the simulated kit."""


class SRV4ServoBoardSimulatedBackend(KitDiscovery, SRV4ServoBoardHardwareBackend):
    """The SR v4 servo board (firmware 2) hardware backend, on the simulated kit."""


if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.simulator._sim_sb_arduino_2019": ["SBArduinoSimulatedBackend"],
            "j5aio.simulator._sim_sr_ruggeduino_fw1": ["SRV4RuggeduinoSimulatedBackend"],
        },
        own=(
            "SRV4MotorBoardSimulatedBackend",
            "SRV4PowerBoardSimulatedBackend",
            "SRV4ServoBoardSimulatedBackend",
        ),
    )
