"""BaseRobot: the object a robot program is built around."""

from __future__ import annotations

import asyncio
import logging
import os
import socket
from types import TracebackType
from typing import Any, ClassVar, Self

import anyio

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.errors import UnableToObtainLock
from j5aio.safety import make_all_safe_uncancellably

__all__ = ["BaseRobot", "UnableToObtainLock"]

LOGGER = logging.getLogger(__name__)

#: The TCP port on localhost whose binding says "a robot is running" (j5's value).
DEFAULT_LOCK_PORT = 10653


class BaseRobot:
    """The base class of robots.

    Use it as an async context manager. On the way in it takes the single-robot lock and
    runs :meth:`setup`, where a subclass finds its boards; on the way out (normally, by
    an exception, by cancellation, or on SIGINT / SIGTERM / SIGHUP) every board is made
    safe; a signal then ends the program with status ``128 + signal``::

        class MyRobot(BaseRobot):
            async def setup(self) -> None:
                self.power_board = (await BoardGroup.get_board_group(
                    PowerBoard, SRV4PowerBoardHardwareBackend)).singular()

        async with MyRobot() as robot:
            ...

    Only one robot may run on a machine at a time: creating a second one, in any process,
    raises :class:`~j5aio.errors.UnableToObtainLock`.
    """

    #: The localhost TCP port used as the machine-wide lock. ``J5AIO_LOCK_PORT`` overrides it.
    lock_port: ClassVar[int] = DEFAULT_LOCK_PORT

    _lock: socket.socket | None

    def __new__(cls, *args: Any, **kwargs: Any) -> Self:
        """Create the robot and take the machine-wide lock (before any ``__init__``)."""
        robot = super().__new__(cls)
        robot._lock = None
        robot._obtain_lock()
        lifetime.install()
        return robot

    def _obtain_lock(self) -> None:
        port = int(os.environ.get("J5AIO_LOCK_PORT", self.lock_port))
        lock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        try:
            lock.bind(("127.0.0.1", port))
        except OSError:
            lock.close()
            raise UnableToObtainLock(
                f"Unable to obtain the robot lock (TCP port {port} on localhost is taken): "
                "another robot program is already running (or another Robot object exists "
                "in this one). Stop it, then try again. To run robots side by side (tests, "
                "say), give each its own free port in the J5AIO_LOCK_PORT environment "
                "variable.",
            ) from None
        self._lock = lock

    def release_lock(self) -> None:
        """Give up the machine-wide lock, so that another robot can be created."""
        if self._lock is not None:
            self._lock.close()
            self._lock = None

    async def setup(self) -> None:
        """Find the robot's boards. Override this in a subclass; it does nothing here."""

    async def make_safe(self) -> None:
        """Make every board safe now. Cancellation cannot interrupt it."""
        await make_all_safe_uncancellably()

    async def __aenter__(self) -> Self:
        self._sigterm_scope = anyio.CancelScope()
        self._sigterm_scope.__enter__()
        self._terminated_by: int | None = None
        self._stop_handling_signals = lifetime.on_terminate(
            asyncio.get_running_loop(), self._on_terminate
        )
        try:
            await self.setup()
        except BaseException:
            await self.__aexit__(None, None, None)
            raise
        return self

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> bool:
        try:
            # Shielded: the robot's own SIGTERM cancellation must not cut this short.
            with anyio.CancelScope(shield=True):
                await make_all_safe_uncancellably()
        finally:
            self._stop_handling_signals()
            self.release_lock()
            swallowed = self._sigterm_scope.__exit__(exc_type, exc, traceback)
        if self._terminated_by is not None:
            raise SystemExit(128 + self._terminated_by)
        return bool(swallowed)

    def _on_terminate(self, signum: int) -> None:
        """SIGTERM / SIGHUP (from :mod:`j5aio.lifetime`): stop the block, then exit."""
        self._terminated_by = signum
        self._sigterm_scope.cancel()

    @staticmethod
    def boards() -> set[Board]:
        """Every board that is set up in this program."""
        return set(Board.BOARDS)

    def __del__(self) -> None:
        self.release_lock()
