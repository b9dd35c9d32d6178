"""The Ruggeduino (firmware 1): its simulated backend."""

from __future__ import annotations

from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend

from .discovery import KitDiscovery

__all__ = ["SRV4RuggeduinoSimulatedBackend"]


class SRV4RuggeduinoSimulatedBackend(KitDiscovery, SRV4RuggeduinoHardwareBackend):
    """The Ruggeduino (firmware 1) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends"  # where it is documented, and imported from
