"""String commands: send a raw text command to a board and get its reply."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["StringCommandComponentInterface"]


class StringCommandComponentInterface(Interface):
    """The coroutine a backend implements to pass raw commands to a board."""

    @abstractmethod
    async def execute_string_command(self, command: str) -> str:
        """Send ``command`` to the board and return its reply."""
        raise NotImplementedError
