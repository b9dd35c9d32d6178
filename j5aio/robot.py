"""BaseRobot: the object a robot program is built around."""

from __future__ import annotations

import asyncio
import logging
import os
import socket
from pathlib import Path
from types import TracebackType
from typing import Any, ClassVar, Self

import anyio

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.competition.clock import MatchClock
from j5aio.competition.metadata import Metadata, Mode, describe, find_usb_sticks, load_metadata
from j5aio.competition.start import wait_for_start
from j5aio.competition.timer import MatchTimer
from j5aio.errors import UnableToObtainLock
from j5aio.safety import make_all_safe_uncancellably

__all__ = ["BaseRobot", "UnableToObtainLock"]

LOGGER = logging.getLogger(__name__)

#: The TCP port on localhost whose binding says "a robot is running" (j5's value).
DEFAULT_LOCK_PORT = 10653


class BaseRobot:
    """The base class of robots.

    Use it as an async context manager. On the way in it takes the single-robot lock and
    runs :meth:`~j5aio.robot.BaseRobot.setup`, where a subclass finds its boards; on the way
    out (normally, by an exception, by cancellation, or on SIGINT / SIGTERM / SIGHUP) every
    board is made safe; a signal then ends the program with status ``128 + signal``::

        class MyRobot(BaseRobot):
            async def setup(self) -> None:
                self.power_board = (await BoardGroup.get_board_group(
                    PowerBoard, SRV4PowerBoardHardwareBackend)).singular()

        async with MyRobot() as robot:
            ...

    Only one robot may run on a machine at a time: creating a second one, in any process,
    raises :class:`~j5aio.errors.UnableToObtainLock`.

    On match day, ``await robot.wait_start()`` waits for the start button and reads the
    match's metadata (:attr:`~j5aio.robot.BaseRobot.zone`, :attr:`~j5aio.robot.BaseRobot.arena`,
    :attr:`~j5aio.robot.BaseRobot.mode`); in a match with a duration the match timer then ends the
    program when the match is over, every board safe, however the program is written (see
    :mod:`j5aio.competition`). Use
    :meth:`~j5aio.robot.BaseRobot.time` and :meth:`~j5aio.robot.BaseRobot.sleep` for timing, so that
    a simulation can run at another speed.
    """

    #: The localhost TCP port used as the machine-wide lock. ``J5AIO_LOCK_PORT`` overrides it.
    lock_port: ClassVar[int] = DEFAULT_LOCK_PORT

    _lock: socket.socket | None
    _metadata: Metadata | None
    _clock: MatchClock
    _match_timer: MatchTimer | None
    _started: bool

    def __new__(cls, *args: Any, **kwargs: Any) -> Self:
        """Create the robot and take the machine-wide lock (before any ``__init__``)."""
        robot = super().__new__(cls)
        robot._lock = None
        robot._metadata = None
        robot._clock = MatchClock()
        robot._match_timer = None
        robot._started = False
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
        self._log_kit()
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

    # -- match day (issue 10) ------------------------------------------------------------

    @property
    def metadata(self) -> Metadata:
        """The match's metadata: read at the start, or looked for now if not started yet.

        :raises ~j5aio.competition.metadata.MetadataError: the metadata file is
            malformed (the message names the file and the field).
        """
        if self._metadata is None:
            self._metadata = load_metadata()
        return self._metadata

    @property
    def arena(self) -> str:
        """The arena the robot is in (``"A"`` when developing)."""
        return self.metadata.arena

    @property
    def zone(self) -> int:
        """The zone the robot starts in (0 when developing)."""
        return self.metadata.zone

    @property
    def mode(self) -> Mode:
        """``Mode.COMP`` in a match, ``Mode.DEV`` otherwise."""
        return self.metadata.mode

    @property
    def is_competition(self) -> bool:
        """Whether the robot is in a match (COMP mode)."""
        return self.metadata.is_competition

    @property
    def usb_stick(self) -> Path | None:
        """The USB stick the metadata came from, else the first one mounted, else ``None``."""
        source = self.metadata.source
        sticks = find_usb_sticks()
        for stick in sticks:
            if source is not None and source.parent == stick:
                return stick
        return sticks[0] if sticks else None

    @property
    def match_timer(self) -> MatchTimer | None:
        """The running match's timer; ``None`` before the start or outside a timed match."""
        return self._match_timer

    def time(self) -> float:
        """Robot seconds since the start (since the robot was made, before the start).

        They are real seconds, except on a simulated kit run at another speed
        (``--time-scale``).
        """
        return self._clock.time()

    async def sleep(self, seconds: float) -> None:
        """Wait ``seconds`` robot seconds (see :meth:`time`), letting other tasks run.

        :raises TypeError: ``seconds`` is not a number.
        :raises ValueError: ``seconds`` is negative or NaN.
        """
        await self._clock.sleep(seconds)

    async def wait_start(self, timeout: float | None = None) -> None:
        """Wait for the start of the match, then read the metadata and start the timer.

        Flashes the run LED (and a KCH's start LED) and beeps once while waiting; the
        start button, the start file a competition runner creates, or
        ``python -m j5aio run``'s console start the robot (:mod:`j5aio.competition.start`).
        In COMP mode with a duration the match timer starts: when it runs out the
        robot's work is cancelled, every board is made safe and the program ends.

        :param timeout: give up after this many seconds; ``None`` waits for ever.
        :raises TimeoutError: nothing started the robot within ``timeout`` seconds.
        :raises ~j5aio.competition.metadata.MetadataError: the metadata file is
            malformed (the message names the file and the field).
        :raises RuntimeError: the robot has started already.
        """
        if self._started:
            raise RuntimeError("the robot has started already: wait_start runs once")
        self._log_kit()
        await wait_for_start(self.boards(), timeout)
        self._started = True
        self._metadata = metadata = load_metadata()
        self._clock = MatchClock(self._clock.scale)
        LOGGER.info("Match metadata: %s", describe(metadata))
        if metadata.is_competition and metadata.duration is not None:
            loop = asyncio.get_running_loop()

            def cancel() -> None:
                loop.call_soon_threadsafe(self._cancel_work)

            self._match_timer = MatchTimer(
                self._clock.to_real(metadata.duration), cancel=cancel
            )
            self._match_timer.start()

    def _log_kit(self) -> None:
        """Log each board found, once (the run log's record of the kit)."""
        if getattr(self, "_kit_logged", False):
            return
        self._kit_logged = True
        for board in sorted(self.boards(), key=lambda b: (b.name, b.serial_number)):
            LOGGER.info(
                "Kit: %s, serial %s, firmware %s",
                board.name,
                board.serial_number,
                board.firmware_version or "(none reported)",
            )

    def _cancel_work(self) -> None:
        """Cancel the robot's ``async with`` block (game over), if it is in one."""
        scope: anyio.CancelScope | None = getattr(self, "_sigterm_scope", None)
        if scope is not None:
            scope.cancel()

    @staticmethod
    def boards() -> set[Board]:
        """Every board that is set up in this program."""
        return set(Board.BOARDS)

    def __del__(self) -> None:
        self.release_lock()
