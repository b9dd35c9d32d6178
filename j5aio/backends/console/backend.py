"""ConsoleBackend: the shared base of the backends of the console environment."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.backend import Backend
from j5aio.backends.console.console import Console

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = ["ConsoleBackend"]


class ConsoleBackend(Backend):
    """A backend that prints what a board would do and asks the user for its readings.

    Discovery always finds one board, with serial number ``"SERIAL"``. The questions and
    messages go through a :class:`~j5aio.backends.console.console.Console`; pass another class to
    the constructor, or set
    :attr:`console_class`, to drive a board from a test or from piped input.

    :param serial: the board's serial number.
    :param console_class: the console to talk through; :attr:`console_class` if not given.
    """

    #: The console class of backends made without one.
    console_class: ClassVar[type[Console]] = Console

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        self._serial = serial
        console = console_class or type(self).console_class
        self._console = console(f"{self.board.__name__}({serial})")

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        """Return the one board of the console environment, serial number ``"SERIAL"``."""
        return [cls.board("SERIAL", cls("SERIAL"))]

    @property
    def serial(self) -> str:
        """The serial number of the board."""
        return self._serial

    @property
    def console(self) -> Console:
        """The console this backend talks through."""
        return self._console

    @property
    def firmware_version(self) -> None:
        """Always ``None``: there is no firmware on the console."""
        return None

    def make_safe_now(self, timeout: float) -> bool:
        """Send nothing: a console drives no hardware (see :meth:`.Backend.make_safe_now`)."""
        return False

    @staticmethod
    def _check_identifier(kind: str, identifier: int, valid: range) -> None:
        """Refuse an identifier the board does not have.

        :raises ValueError: ``identifier`` is not in ``valid``.
        """
        if identifier not in valid:
            raise ValueError(
                f"invalid {kind} identifier {identifier!r}; valid identifiers are "
                f"{valid.start} to {valid.stop - 1}",
            )
