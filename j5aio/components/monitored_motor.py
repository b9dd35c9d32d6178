"""Monitored motors: a motor whose driver reports its current and its faults."""

from __future__ import annotations

from abc import abstractmethod
from typing import cast

from j5aio.components.motor import Motor, MotorInterface

__all__ = ["MonitoredMotor", "MonitoredMotorInterface"]


class MonitoredMotorInterface(MotorInterface):
    """The coroutines a backend implements for motors that report current and faults."""

    @abstractmethod
    async def get_motor_current(self, identifier: int) -> float:
        """Return the current motor ``identifier`` draws, in amps."""
        raise NotImplementedError

    @abstractmethod
    async def get_motor_fault(self, identifier: int) -> bool:
        """Return whether the driver of motor ``identifier`` reports a fault."""
        raise NotImplementedError


class MonitoredMotor(Motor):
    """A :class:`~j5aio.components.motor.Motor` whose driver measures its current and faults.

    :param identifier: the number of the motor on its board.
    :param backend: the backend that drives the motor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[MonitoredMotorInterface]:
        """The interface a backend implements: :class:`MonitoredMotorInterface`."""
        return MonitoredMotorInterface

    async def get_current(self) -> float:
        """Return the current the motor draws, in amps.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await cast(MonitoredMotorInterface, self._backend).get_motor_current(
            self._identifier,
        )

    async def get_has_fault(self) -> bool:
        """Return ``True`` if the motor's driver reports a fault (it pulled its enable low).

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await cast(MonitoredMotorInterface, self._backend).get_motor_fault(
            self._identifier,
        )
