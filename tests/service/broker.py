"""The robot service's tests use j5aio's own broker launcher (j5aio.testing.mosquitto)."""

from __future__ import annotations

from j5aio.testing.mosquitto import MOSQUITTO, Broker, free_port, start_broker

__all__ = ["MOSQUITTO", "Broker", "free_port", "start_broker"]
