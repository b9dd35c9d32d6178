"""The simulated backends of the boards of the kits from 2023 on (firmware 4, the sb2024 Arduino).

As in :mod:`j5aio.simulator.sim_backends`: each is the board's hardware backend whose
``discover`` looks at the boards of :func:`~j5aio.simulator.kit.current_kit` made from its
kind's simulators, and nothing else. They live apart from the older boards' so that a
program on an older kit imports none of these boards' backends; and each Arduino's is
imported, with its hardware backend, the first time it is looked up here, so that a kit
imports the backend of the Arduino it has only.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)

from .discovery import KitDiscovery

if TYPE_CHECKING:
    from ._sim_sb_arduino_2024 import (
        SBArduino2024SimulatedBackend as SBArduino2024SimulatedBackend,
    )
    from ._sim_sr_arduino_fw2 import SRArduinoSimulatedBackend as SRArduinoSimulatedBackend


class SRV4PowerBoardFw4SimulatedBackend(KitDiscovery, SRV4PowerBoardFw4HardwareBackend):
    """The SR v4 power board (firmware 4) hardware backend, on the simulated kit."""


class SRV4MotorBoardFw4SimulatedBackend(KitDiscovery, SRV4MotorBoardFw4HardwareBackend):
    """The SR v4 motor board (firmware 4) hardware backend, on the simulated kit."""


class SRV4ServoBoardFw4SimulatedBackend(KitDiscovery, SRV4ServoBoardFw4HardwareBackend):
    """The SR v4 servo board (firmware 4.3) hardware backend, on the simulated kit."""


class SBServoBoardSimulatedBackend(KitDiscovery, SBServoBoardHardwareBackend):
    """The SourceBots servo board (firmware 4.4) hardware backend, on the simulated kit."""


if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.simulator._sim_sr_arduino_fw2": ["SRArduinoSimulatedBackend"],
            "j5aio.simulator._sim_sb_arduino_2024": ["SBArduino2024SimulatedBackend"],
        },
        own=(
            "SBServoBoardSimulatedBackend",
            "SRV4MotorBoardFw4SimulatedBackend",
            "SRV4PowerBoardFw4SimulatedBackend",
            "SRV4ServoBoardFw4SimulatedBackend",
        ),
    )
