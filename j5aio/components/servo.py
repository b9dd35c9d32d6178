"""Servos: an actuator moved to a position between -1 and 1, or left unpowered."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["ServoInterface", "ServoPosition"]

ServoPosition = float | None
"""A servo position: a float in [-1, 1], or ``None`` for unpowered."""


class ServoInterface(Interface):
    """The coroutines a backend implements to drive servos."""

    @abstractmethod
    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return the position of servo ``identifier`` (``None`` when unpowered)."""
        raise NotImplementedError

    @abstractmethod
    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Move servo ``identifier`` to ``position`` (already validated by the component)."""
        raise NotImplementedError
