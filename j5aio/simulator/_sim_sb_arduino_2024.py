"""The SourceBots Arduino (sb2024 firmware): its simulated backend."""

from __future__ import annotations

from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend

from .discovery import KitDiscovery

__all__ = ["SBArduino2024SimulatedBackend"]


class SBArduino2024SimulatedBackend(KitDiscovery, SBArduino2024HardwareBackend):
    """The SourceBots Arduino (sb2024 firmware) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from
