"""Ultrasound distance sensors, driven on a trigger pin and an echo pin."""

from __future__ import annotations

from abc import abstractmethod
from datetime import timedelta

from j5aio.components.component import Interface

__all__ = ["UltrasoundInterface"]


class UltrasoundInterface(Interface):
    """The coroutines a backend implements to read ultrasound sensors."""

    @abstractmethod
    async def get_ultrasound_pulse(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> timedelta | None:
        """Return how long the echo took, or ``None`` if no echo came back."""
        raise NotImplementedError

    @abstractmethod
    async def get_ultrasound_distance(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> float | None:
        """Return the distance to the nearest object in metres, or ``None`` if no echo."""
        raise NotImplementedError
