"""BaseRobot: the object a robot program is built around."""

from __future__ import annotations

import asyncio
import contextlib
import importlib
import logging
import os
import socket
import sys
from collections.abc import Awaitable, Callable, Iterable
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, ClassVar, Final, Self

import anyio

from j5aio.boards.board import Board
from j5aio.competition import service_state
from j5aio.competition.clock import MatchClock
from j5aio.components._checks import check_timeout
from j5aio.errors import UnableToObtainLock
from j5aio.safety import hooks as safety_hooks
from j5aio.safety import make_all_safe_uncancellably

if TYPE_CHECKING:
    from j5aio.competition.metadata import Metadata, Mode
    from j5aio.competition.timer import MatchTimer

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
    :mod:`j5aio.competition`). ``wait_for_start=True`` makes entering the robot wait for
    the start, as the kits' own libraries do when their robot is made. In a match, the
    start starts the match timer even if the program never waits for it
    (:meth:`~j5aio.robot.BaseRobot.watch_for_start`). Use
    :meth:`~j5aio.robot.BaseRobot.time` and :meth:`~j5aio.robot.BaseRobot.sleep` for timing, so that
    a simulation can run at another speed.

    :param wait_for_start: wait for the start on entering (after
        :meth:`~j5aio.robot.BaseRobot.setup`), as :meth:`~j5aio.robot.BaseRobot.wait_start`
        does.
    :raises TypeError: ``wait_for_start`` is not a bool.
    """

    #: The localhost TCP port used as the machine-wide lock. ``J5AIO_LOCK_PORT`` overrides it.
    lock_port: ClassVar[int] = DEFAULT_LOCK_PORT

    _lock: socket.socket | None
    _metadata: Metadata | None
    _no_metadata_at_start: bool
    _clock: MatchClock
    _match_timer: MatchTimer | None
    _started: bool
    _waits_for_start_on_entry: bool
    _wait_start_returned: bool
    _waiting: bool
    _watcher: asyncio.Task[None] | None
    _watch_scope: anyio.CancelScope | None
    _watch_loop: asyncio.AbstractEventLoop | None
    _watch_error: Exception | None
    _service: Any

    def __new__(cls, *args: Any, **kwargs: Any) -> Self:
        """Create the robot and take the machine-wide lock (before any ``__init__``)."""
        robot = super().__new__(cls)
        robot._lock = None
        robot._metadata = None
        robot._no_metadata_at_start = False
        robot._clock = MatchClock()
        robot._match_timer = None
        robot._started = False
        robot._waits_for_start_on_entry = False
        robot._wait_start_returned = False
        robot._waiting = False
        robot._watcher = None
        robot._watch_scope = None
        robot._watch_loop = None
        robot._watch_error = None
        robot._service = None
        robot._obtain_lock()
        safety_hooks.install()
        return robot

    def __init__(self, *, wait_for_start: bool = False) -> None:
        if not isinstance(wait_for_start, bool):
            self.release_lock()
            raise TypeError(f"wait_for_start must be True or False, not {wait_for_start!r}")
        self._waits_for_start_on_entry = wait_for_start

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
        self._stop_handling_signals = safety_hooks.on_terminate(
            asyncio.get_running_loop(), self._on_terminate
        )
        try:
            await self._start_service()
            await self.setup()
            await self.after_setup()
        except BaseException:
            await self.__aexit__(None, None, None)
            raise
        return self

    async def after_setup(self) -> None:
        """What entering the robot does once :meth:`setup` has found the boards.

        It starts the robot service's client (if the service is configured), logs the
        kit, starts :meth:`watch_for_start`, and, if the robot was made with
        ``wait_for_start=True``, waits for the start (:meth:`wait_start`).
        ``async with`` calls it; the sync facade calls it after ``setup``; a subclass
        that overrides ``__aenter__`` must call it.

        :raises ~j5aio.competition.metadata.MetadataError: the metadata is unusable.
        """
        await self._start_service()
        self._log_kit()
        await self.watch_for_start()
        if self._waits_for_start_on_entry and not self._wait_start_returned:
            await self.wait_start()

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> bool:
        try:
            # Shielded: the robot's own SIGTERM cancellation must not cut this short.
            with anyio.CancelScope(shield=True):
                await self._stop_watching()
                await make_all_safe_uncancellably()
                await self._stop_service()
        finally:
            self._stop_handling_signals()
            self.release_lock()
            swallowed = self._sigterm_scope.__exit__(exc_type, exc, traceback)
        if self._terminated_by is not None:
            raise SystemExit(128 + self._terminated_by)
        return bool(swallowed)

    def _on_terminate(self, signum: int) -> None:
        """SIGTERM / SIGHUP (from :mod:`j5aio.safety.hooks`): stop the block, then exit."""
        self._terminated_by = signum
        self._sigterm_scope.cancel()

    # -- the robot service ---------------------------------------------------------------

    async def _start_service(self) -> None:
        """Start the robot service's client, if :mod:`j5aio.service` is there and configured.

        The service (astoria over MQTT) gives the match's metadata, the team's USB stick
        and the remote start (:mod:`j5aio.competition.service_state`). It is optional:
        without the package, or where no service is configured, nothing happens (and
        where nothing configures it, the package is not even imported).
        """
        if self._service is not None:
            return
        if not service_state.service_may_be_configured():
            LOGGER.debug("Robot service: not configured here")
            return
        try:
            service = importlib.import_module("j5aio.service")
        except ImportError:  # (a build of j5aio without the service client)
            LOGGER.debug("No robot service client in this j5aio", exc_info=True)
            return
        self._service = await service.start_service()

    async def _stop_service(self) -> None:
        service, self._service = self._service, None
        if service is not None:
            await service.stop()

    # -- match day ---------------------------------------------------------------------

    @property
    def metadata(self) -> Metadata:
        """The match's metadata: fixed at the start; until then, what it is now.

        Before the start, what the robot service last said wins (it may change the zone
        or the mode while the robot waits), else the metadata file, read once. From the
        start on it is what it was at the start, whatever the service says later.
        See :func:`~j5aio.competition.metadata.load_metadata` for where it comes from.

        :raises ~j5aio.competition.metadata.MetadataError: the metadata file is
            malformed (the message names the file and the field).
        """
        if not self._started:
            live = service_state.metadata()
            if live is not None:
                return live
        if self._metadata is None:
            from j5aio.competition import metadata

            self._metadata = (
                metadata.DEV_DEFAULTS if self._no_metadata_at_start else metadata.load_metadata()
            )
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
        """The team's USB stick, or ``None``.

        The one the robot service says holds the team's code; else the stick the metadata
        came from; else the first one mounted.
        """
        usercode = service_state.usercode_path()
        if usercode is not None:
            return usercode
        from j5aio.competition.metadata import find_usb_sticks

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

    @property
    def started(self) -> bool:
        """Whether the robot has started (by :meth:`wait_start` or :meth:`watch_for_start`)."""
        return self._started

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
        start button, the start file a competition runner creates, a remote start from
        the robot service, or ``python -m j5aio run``'s console start the robot
        (:mod:`j5aio.competition.start`). In COMP mode with a duration the match timer
        starts: when it runs out the robot's work is cancelled, every board is made safe
        and the program ends. If the start came already (:meth:`watch_for_start` saw
        it), this returns at once.

        :param timeout: give up after this many seconds; ``None`` waits for ever.
        :raises TimeoutError: nothing started the robot within ``timeout`` seconds.
        :raises ~j5aio.competition.metadata.MetadataError: the metadata file is
            malformed (the message names the file and the field).
        :raises RuntimeError: ``wait_start`` has returned already: it runs once.
        """
        limit = check_timeout(timeout)
        if self._wait_start_returned:
            raise RuntimeError("the robot has started already: wait_start runs once")
        self._log_kit()
        watcher = self._watcher
        if watcher is not None and not watcher.done():
            with anyio.fail_after(limit):
                await asyncio.shield(watcher)  # a timeout leaves the watcher watching
        error, self._watch_error = self._watch_error, None
        if error is not None:  # the watcher failed: say why (a later call waits again)
            raise error
        if not self._started:  # no watcher, or it failed: wait here
            self._waiting = True
            try:
                how = await _wait_for_start()(self.boards(), limit)
            finally:
                self._waiting = False
            self._begin_match(how)
        self._wait_start_returned = True

    async def watch_for_start(self) -> None:
        """In a match, start the match timer when the start comes, waited for or not.

        From now until the start, while the robot is in COMP mode (by its metadata,
        which the robot service may change), a background task waits for the start as
        :meth:`wait_start` does: the button, the start file, or a remote start then
        starts the match and its timer even if the program never calls
        :meth:`wait_start` (a later :meth:`wait_start` returns at once). In DEV mode
        nothing is watched: the program waits when it wants to. Entering the robot calls
        this; calling it again does nothing. It returns at once.

        :raises ~j5aio.competition.metadata.MetadataError: the metadata is unusable:
            in a match the robot must not run on a guess.
        """
        if self._watch_loop is not None or self._started:
            return
        nothing_to_read = (
            self._metadata is None
            and service_state.metadata() is None
            and not _metadata_may_be_there()
        )
        if nothing_to_read:  # (so development mode, and the metadata module is not loaded)
            self._no_metadata_at_start = True
        else:
            self.metadata  # noqa: B018 - read now: unusable metadata is an error before the match
        self._watch_loop = asyncio.get_running_loop()
        service_state.add_listener(self._on_service_change)
        if not nothing_to_read:
            self._watch_if_in_a_match()

    def _on_service_change(self) -> None:
        """The service's metadata changed (on its thread): look again, on the robot's loop."""
        loop = self._watch_loop
        if loop is not None:
            with contextlib.suppress(RuntimeError):  # the loop has closed: nothing to do
                loop.call_soon_threadsafe(self._look_again)

    def _look_again(self) -> None:
        from j5aio.competition.metadata import MetadataError

        try:
            self._watch_if_in_a_match()
        except MetadataError as error:
            LOGGER.error("The match's metadata is unusable: %s", error)

    def _watch_if_in_a_match(self) -> None:
        if self._started or self._waiting or self._watcher is not None:
            return
        metadata = self.metadata
        if not metadata.is_competition:
            return
        from j5aio.competition.metadata import describe

        LOGGER.info("In a match (%s): watching for the start", describe(metadata))
        self._watch_scope = None
        self._watcher = asyncio.get_running_loop().create_task(
            self._watch(), name="j5aio start watcher"
        )

    async def _watch(self) -> None:
        # (the scope is made here: anyio needs a running task to make one)
        with anyio.CancelScope() as self._watch_scope:
            try:
                how = await _wait_for_start()(self.boards(), None)
                self._begin_match(how)
            except Exception as exc:  # a board or the metadata failed: say so; the
                # program's wait_start() raises it, and waits itself when called again
                LOGGER.error("Watching for the start failed: %s", exc)
                self._watch_error = exc
                self._watcher = None

    async def _stop_watching(self) -> None:
        """Stop watching for the start (on leaving the robot)."""
        service_state.remove_listener(self._on_service_change)
        self._watch_loop = None
        watcher, scope = self._watcher, self._watch_scope
        if watcher is None or watcher.done():
            return
        if scope is None:
            watcher.cancel()  # it has not run yet: nothing of it to unwind
        else:
            scope.cancel()
        await asyncio.wait([watcher])

    def _begin_match(self, how: str) -> None:
        """The start has come (by ``how``): fix the metadata and start the match timer."""
        from j5aio.competition.metadata import describe, load_metadata

        metadata = load_metadata()
        self._started = True
        self._metadata = metadata
        self._clock = MatchClock(self._clock.scale)
        LOGGER.info("Match metadata (started by the %s): %s", how, describe(metadata))
        if metadata.is_competition and metadata.duration is not None:
            loop = asyncio.get_running_loop()

            def cancel() -> None:
                loop.call_soon_threadsafe(self._cancel_work)

            self._match_timer = _match_timer()(
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


# Where match metadata may be, for a quick look that reads nothing: the variables and
# folders :func:`j5aio.competition.metadata.load_metadata` reads (named as there; a test
# checks that they agree), so that a robot with none imports no metadata reader.
_METADATA_VARIABLES: Final = ("J5AIO_METADATA", "SBOT_METADATA_PATH")
_MEDIA_ROOTS_VARIABLE: Final = "J5AIO_MEDIA_ROOTS"
_DEFAULT_MEDIA_ROOTS: Final = ("/media", "/run/media")


def _metadata_may_be_there() -> bool:
    """Whether there may be match metadata to read: False only where there is surely none.

    That is: no variable names a metadata file or folder, and every folder where USB
    sticks are mounted is empty or missing.
    """
    if any(os.environ.get(variable) for variable in _METADATA_VARIABLES):
        return True
    override = os.environ.get(_MEDIA_ROOTS_VARIABLE)
    roots = _DEFAULT_MEDIA_ROOTS if override is None else override.split(os.pathsep)
    for root in filter(None, roots):
        try:
            with os.scandir(root) as entries:
                if next(entries, None) is not None:
                    return True
        except OSError:
            continue  # (no such folder: no stick there)
    return False


_LAZY: Final = {
    "MatchTimer": "j5aio.competition.timer",
    "wait_for_start": "j5aio.competition.start",
}


def __getattr__(name: str) -> Any:  # PEP 562: what a match needs, imported for a match
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_LAZY[name]), name)
    globals()[name] = value
    return value


def _wait_for_start() -> Callable[[Iterable[Board], float | None], Awaitable[str]]:
    """:func:`~j5aio.competition.start.wait_for_start`, looked up here (a test may replace it)."""
    found: Callable[[Iterable[Board], float | None], Awaitable[str]]
    found = sys.modules[__name__].wait_for_start
    return found


def _match_timer() -> type[MatchTimer]:
    """:class:`~j5aio.competition.timer.MatchTimer`, looked up here (a test may replace it)."""
    found: type[MatchTimer] = sys.modules[__name__].MatchTimer
    return found
