"""Servos: an actuator moved to a position between -1 and 1, or left unpowered."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components._checks import check_number
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["Servo", "ServoInterface", "ServoPosition"]

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


class Servo(IdentifiedComponent[ServoInterface]):
    """A servo: an actuator that moves to a position and holds it.

    Positions run from -1 (one end of its travel) to 1 (the other end). ``None``
    unpowers the servo, so it can be turned by hand.

    :param identifier: the number of the servo on its board.
    :param backend: the backend that drives the servo.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[ServoInterface]:
        """The interface a backend implements to drive servos: :class:`ServoInterface`."""
        return ServoInterface

    async def get_position(self) -> ServoPosition:
        """Return the servo's position in [-1, 1], or ``None`` if it is unpowered.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_servo_position(self._identifier)

    async def set_position(self, position: ServoPosition) -> None:
        """Move the servo to ``position``, or unpower it with ``None``.

        :param position: a number between -1 and 1, or ``None``.
        :raises TypeError: ``position`` is neither a number nor ``None`` (a bool is
            refused too).
        :raises ValueError: ``position`` is outside [-1, 1], or NaN.
        :raises NotSupportedByHardwareError: (from the backend) the board cannot unpower
            a servo.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        # A float in range (the common case) is checked here, without a call (an
        # abstract-class check of the number's type is one); anything else by
        # check_number.
        if position is not None and (
            type(position) is not float or not -1.0 <= position <= 1.0
        ):
            position = check_number(
                position,
                name="servo position",
                low=-1.0,
                high=1.0,
                allowed="a float between -1 and 1, or None (unpowered)",
            )
        await self._backend.set_servo_position(self._identifier, position)
