"""The console backend of the Student Robotics Ruggeduino."""

from __future__ import annotations

from j5aio.backends.console.arduino import ArduinoConsoleBackend
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.components.string_command import StringCommandComponentInterface

__all__ = ["SRV4RuggeduinoConsoleBackend"]


class SRV4RuggeduinoConsoleBackend(StringCommandComponentInterface, ArduinoConsoleBackend):
    """The Ruggeduino on the console: its pins, and the replies to string commands.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = Ruggeduino

    async def execute_string_command(self, command: str) -> str:
        """Ask for the board's reply to ``command``."""
        return await self._console.read(f'Response to string command "{command}" [str]', str)
