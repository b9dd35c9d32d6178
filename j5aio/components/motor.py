"""Motors: a DC motor driven at a power between full reverse and full forward."""

from __future__ import annotations

from abc import abstractmethod
from enum import Enum

from j5aio.components._checks import check_number
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["Motor", "MotorInterface", "MotorSpecialState", "MotorState", "check_motor_state"]


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


class Motor(IdentifiedComponent[MotorInterface]):
    """A DC motor, driven at a power between full reverse (-1) and full forward (1).

    ``await motor.set_power(0.5)`` drives forward at half power, ``-1`` drives backwards
    at full power, ``0`` stops driving. ``MotorSpecialState.BRAKE`` holds the motor
    still and ``MotorSpecialState.COAST`` lets it spin freely.

    :param identifier: the number of the motor on its board.
    :param backend: the backend that drives the motor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[MotorInterface]:
        """The interface a backend implements to drive motors: :class:`MotorInterface`."""
        return MotorInterface

    async def get_power(self) -> MotorState:
        """Return the motor's power in [-1, 1], or its :class:`MotorSpecialState`.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_motor_state(self._identifier)

    async def set_power(self, power: MotorState) -> None:
        """Drive the motor at ``power``.

        :param power: a number between -1 (full reverse) and 1 (full forward), or
            ``MotorSpecialState.BRAKE`` / ``MotorSpecialState.COAST``.
        :raises TypeError: ``power`` is neither a number nor a special state (a bool
            is refused too).
        :raises ValueError: ``power`` is outside [-1, 1], or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        # A float in range (the common case) is checked here, without a call; anything
        # else (an int, a special state, NaN, bad input) by check_motor_state.
        if type(power) is not float or not -1.0 <= power <= 1.0:
            power = check_motor_state(power)
        await self._backend.set_motor_state(self._identifier, power)


def check_motor_state(power: object, *, name: str = "motor power") -> MotorState:
    """Return ``power`` if a motor can be set to it, with an int turned into a float.

    Boards use this to check a motor state they are given, such as a safe state.

    :param power: the value to check.
    :param name: what the value is, for the error message.
    :raises TypeError: ``power`` is neither a number nor a :class:`MotorSpecialState`
        (a bool is refused too).
    :raises ValueError: ``power`` is outside [-1, 1], or NaN.
    """
    if isinstance(power, MotorSpecialState):
        return power
    return check_number(
        power,
        name=name,
        low=-1.0,
        high=1.0,
        allowed="a float between -1 and 1, or MotorSpecialState.BRAKE / COAST",
    )
