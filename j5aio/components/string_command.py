"""String commands: send a raw text command to a board and get its reply."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components._checks import describe
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["StringCommandComponent", "StringCommandComponentInterface"]


class StringCommandComponentInterface(Interface):
    """The coroutine a backend implements to pass raw commands to a board."""

    @abstractmethod
    async def execute_string_command(self, command: str) -> str:
        """Send ``command`` to the board and return its reply."""
        raise NotImplementedError


class StringCommandComponent(IdentifiedComponent[StringCommandComponentInterface]):
    """A raw text channel to a board, for boards that run custom firmware.

    ``await cmd.execute("X")`` (or ``await cmd("X")``) sends ``X`` and returns the
    board's reply.

    :param identifier: the number of the component on its board.
    :param backend: the backend that passes the commands on.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[StringCommandComponentInterface]:
        """The interface a backend implements for string commands."""
        return StringCommandComponentInterface

    async def execute(self, command: str) -> str:
        """Send ``command`` to the board and return its reply.

        :raises TypeError: ``command`` is not a str.
        :raises ValueError: ``command`` is empty.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        if not isinstance(command, str):
            raise TypeError(f"a command must be a non-empty str; got {describe(command)}")
        if not command:
            raise ValueError("a command must be a non-empty str; got ''")
        return await self._backend.execute_string_command(command)

    async def __call__(self, command: str) -> str:
        """Send ``command`` to the board and return its reply, as :meth:`execute`."""
        return await self.execute(command)
