"""The Bee Board's simulated backend: its hardware backend, on the simulated kit."""

from __future__ import annotations

from j5aio.simulator.discovery import KitDiscovery

from .backend import BeeBackend

__all__ = ["BeeSimulatedBackend"]


class BeeSimulatedBackend(KitDiscovery, BeeBackend):
    """:class:`~beekit.backend.BeeBackend` on the simulated kit: only where it looks differs."""
