"""The Board base class: a group of components reached through one backend."""

from __future__ import annotations

import logging
from abc import ABC, abstractmethod
from typing import TYPE_CHECKING, ClassVar

from j5aio.safety import orderly, registry

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["Board"]

LOGGER = logging.getLogger(__name__)


class Board(ABC):
    """A physical board: a set of components driven through one backend.

    Every board made is in the safety registry (:mod:`j5aio.safety.registry`) until it
    is closed, which makes it safe through its backend's
    :meth:`~j5aio.backends.backend.Backend.make_safe_now` however the program ends; every
    board that has been set up is also in :attr:`BOARDS`, so that :meth:`make_all_safe`
    can reach all of them when a program stops. Making a board installs nothing in the
    process (the entry points install the process hooks: :mod:`j5aio.safety.hooks`).

    :param serial_number: the board's serial number, as the backend found it.
    :param backend: the backend that drives this board.
    """

    #: A human-friendly name for this kind of board.
    name: ClassVar[str] = "Board"

    #: Every board that is set up and not yet closed (the registry's set of them).
    BOARDS: ClassVar[set[Board]] = registry.SET_UP

    #: Whether this board is made safe after every other one: a board that powers the
    #: others (the power board) must not cut their power before they stopped.
    MAKE_SAFE_LAST: ClassVar[bool] = False

    def __init__(self, serial_number: str, backend: Backend) -> None:
        self._serial_number = serial_number
        self._backend = backend
        self._is_set_up = False
        self._is_closed = False
        registry.track(self)

    @property
    def serial_number(self) -> str:
        """The serial number of the board."""
        return self._serial_number

    @property
    def firmware_version(self) -> str | None:
        """The firmware version the board reported, or ``None`` if it has none."""
        return self._backend.firmware_version

    @property
    def backend(self) -> Backend:
        """The backend that drives this board."""
        return self._backend

    @staticmethod
    @abstractmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on this board; a backend must implement their interfaces."""
        raise NotImplementedError

    @abstractmethod
    async def make_safe(self) -> None:
        """Put every component of the board in its safe state (motors stopped, ...)."""
        raise NotImplementedError

    async def setup(self) -> None:
        """Bring the board into its initial state and register it for :meth:`make_all_safe`.

        Runs :meth:`_setup` once, however often it is called. Backends and board groups
        call it; user code does not need to.
        """
        if self._is_set_up:
            return
        await self._setup()
        self._is_set_up = True
        self._is_closed = False
        Board.BOARDS.add(self)

    async def _setup(self) -> None:  # noqa: B027 - optional hook
        """Apply the initial state of the board's components (a hook for subclasses)."""

    async def close(self) -> None:
        """Release the board's port and forget it. The board is not made safe first."""
        if self._is_closed:
            return
        self._is_closed = True
        Board.BOARDS.discard(self)
        registry.untrack(self)
        await self._backend.close()

    def close_now(self) -> None:
        """Release the board's port at once, synchronously, and forget it (for exit paths)."""
        if self._is_closed:
            return
        self._is_closed = True
        Board.BOARDS.discard(self)
        registry.untrack(self)
        # A stand-in backend that is not a Backend (a test's) may have nothing to close.
        close_now = getattr(self._backend, "close_now", None)
        if close_now is not None:
            close_now()

    @staticmethod
    async def make_all_safe() -> list[BaseException]:
        """Make every set-up board safe, all at once (those that power the others last).

        A board that fails to become safe does not stop the others: its error is logged
        and returned, so that the caller can decide what to do with it.

        :returns: the errors raised by boards that could not be made safe.
        """
        return await orderly.make_all_safe()

    def __str__(self) -> str:
        return f"{self.name} - {self.serial_number}"

    def __repr__(self) -> str:
        return f"<{type(self).__name__} serial_number={self.serial_number!r}>"


async def _make_all_safe_as_the_board_class_does() -> list[BaseException]:
    # Board.make_all_safe is looked up at each call: a kit may have replaced it.
    return await Board.make_all_safe()


# The orderly path's uncancellable pass runs through Board.make_all_safe (the safety
# package sits below the boards, so it is handed the call rather than importing Board).
orderly.run_pass_through(_make_all_safe_as_the_board_class_does)
