"""BaseRobot: the object a robot program is built around."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import signal
import socket
import threading
from types import TracebackType
from typing import Any, ClassVar, Self

import anyio

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
    an exception, by cancellation, or on SIGINT / SIGTERM) every board is made safe::

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
        return robot

    def _obtain_lock(self) -> None:
        port = int(os.environ.get("J5AIO_LOCK_PORT", self.lock_port))
        lock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        try:
            lock.bind(("127.0.0.1", port))
        except OSError:
            lock.close()
            raise UnableToObtainLock(
                "Unable to obtain the robot lock: another robot program is already running "
                "(or another Robot object exists in this one). Stop it, then try again.",
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
        self._terminated = False
        self._signal_installed = self._install_sigterm_handler()
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
            await make_all_safe_uncancellably()
        finally:
            if self._signal_installed:
                with contextlib.suppress(Exception):
                    asyncio.get_running_loop().remove_signal_handler(signal.SIGTERM)
            self.release_lock()
            swallowed = self._sigterm_scope.__exit__(exc_type, exc, traceback)
        if self._terminated:
            raise SystemExit(128 + signal.SIGTERM)
        return bool(swallowed)

    def _install_sigterm_handler(self) -> bool:
        if threading.current_thread() is not threading.main_thread():
            return False
        try:
            asyncio.get_running_loop().add_signal_handler(signal.SIGTERM, self._on_sigterm)
        except (NotImplementedError, RuntimeError):  # pragma: no cover - Windows
            return False
        return True

    def _on_sigterm(self) -> None:
        LOGGER.error("Terminated by SIGTERM: making every board safe.")
        self._terminated = True
        self._sigterm_scope.cancel()

    @staticmethod
    def boards() -> set[Board]:
        """Every board that is set up in this program."""
        return set(Board.BOARDS)

    def __del__(self) -> None:
        self.release_lock()
