"""The SR Arduino (firmware 2): its simulated backend."""

from __future__ import annotations

from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend

from .discovery import KitDiscovery

__all__ = ["SRArduinoSimulatedBackend"]


class SRArduinoSimulatedBackend(KitDiscovery, SRArduinoHardwareBackend):
    """The SR Arduino (firmware 2) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from
