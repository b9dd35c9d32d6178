"""Motors: a DC motor driven at a power between full reverse and full forward."""

from __future__ import annotations

from abc import abstractmethod
from enum import Enum

from j5aio.components.component import Interface

__all__ = ["MotorInterface", "MotorSpecialState", "MotorState"]


class MotorSpecialState(Enum):
    """The states of a motor other than a power level."""

    COAST = 0  #: the motor is disconnected and spins freely
    BRAKE = 1  #: the motor's terminals are shorted, so it resists turning


MotorState = float | MotorSpecialState
"""What a motor can be set to: a power in [-1, 1] or a :class:`MotorSpecialState`."""


class MotorInterface(Interface):
    """The coroutines a backend implements to drive motors."""

    @abstractmethod
    async def get_motor_state(self, identifier: int) -> MotorState:
        """Return the state of motor ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Set motor ``identifier`` to ``power`` (already validated by the component)."""
        raise NotImplementedError
