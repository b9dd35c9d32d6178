"""The SourceBots Arduino (2019 firmware): its simulated backend."""

from __future__ import annotations

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend

from .discovery import KitDiscovery

__all__ = ["SBArduinoSimulatedBackend"]


class SBArduinoSimulatedBackend(KitDiscovery, SBArduinoHardwareBackend):
    """The SourceBots Arduino (2019 firmware) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends"  # where it is documented, and imported from
