"""The match supervisor: game over from outside the program's interpreter.

The match timer (:mod:`j5aio.competition.timer`) is a thread of the program, so a program
can hold it back: C code that keeps the GIL (``sum(range(4 * 10**8))``), a huge
``sys.setswitchinterval``, or a forked child that keeps running after the program ends.
So in a timed match ``j5aio run`` does not run the program itself: it runs it as a child
(``python -m j5aio run`` again, with the same arguments) in a process group of its own,
and watches it from its own process, which no program code runs in:

1. The child tells the supervisor when the match starts and when it ends, over a pipe
   whose descriptor it finds in :data:`SUPERVISOR_FD_VARIABLE` (the supervisor cannot
   see the start itself: it may come from the start button, the start file or the
   robot service). The lines are ``start <end>`` (the ``time.monotonic()`` the match
   ends at, a clock every process of the machine shares) and ``safe`` (game over made
   every board safe in the program).
2. If the program has not reported its boards safe :data:`SAFE_WAIT` seconds after the
   end, the supervisor ends the program's whole process group at once (``SIGKILL``)
   and makes the boards safe itself (:func:`make_boards_safe`).
3. :data:`GROUP_WAIT` seconds after the end at the latest, or as soon as the program
   has ended, whatever is left of the process group (a forked child) is ended too.

Making the boards safe from the supervisor: on the hardware the supervisor finds the
boards plugged in, as the program did, and sends each its safe command through its own
backend (each board kind knows its backends). On the simulated kit the boards are
simulators inside the program's process: once that process is ended there is no board
left that could drive, so ending it is what makes them safe. The console environment
drives nothing.

The supervisor passes Ctrl-C, SIGTERM and SIGHUP on to the program's process group, and
ends with the program's exit status, or 0 after game over.
"""

from __future__ import annotations

import contextlib
import os
import select
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from types import FrameType
from typing import Final

__all__ = [
    "GROUP_WAIT",
    "NO_SUPERVISOR_VARIABLE",
    "SAFE_WAIT",
    "SUPERVISOR_FD_VARIABLE",
    "adopt",
    "is_supervised",
    "make_boards_safe",
    "prepare_boards_safe",
    "report_log",
    "report_safe",
    "report_start",
    "supervise",
]

#: The environment variable through which a supervised program finds its pipe.
SUPERVISOR_FD_VARIABLE: Final = "J5AIO_SUPERVISOR_FD"
#: Set to ``1`` by a test harness that must run the program in its own process (to look
#: into the simulated kit): ``j5aio run`` then runs it there, with the in-process match
#: timer only. It is read before the program runs, so a program cannot set it for itself.
NO_SUPERVISOR_VARIABLE: Final = "J5AIO_NO_SUPERVISOR"
#: Seconds after the end by which the program must have reported its boards safe.
SAFE_WAIT: Final = 0.03
#: Seconds after the end by which the program's whole process group is ended.
GROUP_WAIT: Final = 0.5

#: The pipe to the supervisor, in a supervised program (``None``: not supervised).
_pipe: int | None = None
_adopted = False


# -- the program's side -----------------------------------------------------------------------


def adopt() -> bool:
    """Take the pipe to the supervisor from the environment, once.

    The variable is removed, so that programs this one starts are not taken for it.

    :returns: whether this process is supervised.
    """
    global _pipe, _adopted
    if not _adopted:
        _adopted = True
        text = os.environ.pop(SUPERVISOR_FD_VARIABLE, "")
        with contextlib.suppress(ValueError):
            _pipe = int(text)
    return _pipe is not None


def is_supervised() -> bool:
    """Whether this process runs under a match supervisor."""
    return adopt()


def _report(line: str) -> None:
    if not adopt() or _pipe is None:
        return
    with contextlib.suppress(OSError):  # the supervisor is gone: nothing to tell
        os.write(_pipe, f"{line}\n".encode())


def report_start(ends_at: float) -> None:
    """Tell the supervisor (if any) that the match ends at ``ends_at`` (``time.monotonic``)."""
    _report(f"start {ends_at!r}")


def report_safe() -> None:
    """Tell the supervisor (if any) that game over made every board safe."""
    _report("safe")


def report_log(path: os.PathLike[str] | str) -> None:
    """Tell the supervisor (if any) where the run log is, for its own game-over line."""
    _report(f"log {os.fspath(path)}")


# -- the supervisor's side --------------------------------------------------------------------


def _has_boards_left(environment: str | None) -> bool:
    """Whether boards of ``environment`` outlive the program's process (the hardware's)."""
    return environment in (None, "", "hardware")


def prepare_boards_safe(environment: str | None) -> None:
    """Load what :func:`make_boards_safe` needs now, so that it loses no time at the end.

    The supervisor calls it while the program starts (it saves about a third of a second
    of imports after the end).
    """
    if not _has_boards_left(environment):
        return
    import anyio  # noqa: F401 - loaded now, used at the end

    from j5aio.environments import hardware_environment
    from j5aio.safety import orderly  # noqa: F401 - loaded now, used at the end

    hardware_environment().backends  # noqa: B018 - loads every hardware backend


def make_boards_safe(environment: str | None) -> None:
    """Make the boards safe after the program's processes were ended.

    :param environment: the program's environment (``J5AIO_ENV``: ``hardware``, ``sim``,
        ``console``; ``None`` or empty: the hardware). Only the hardware has boards left
        to stop: the simulated kit ended with the program's process.
    """
    if not _has_boards_left(environment):
        return
    import anyio

    anyio.run(_make_hardware_safe)


async def _make_hardware_safe() -> None:
    from j5aio.boards.board import Board
    from j5aio.environments import hardware_environment
    from j5aio.lifetime import open_boards
    from j5aio.safety import make_all_safe_uncancellably

    environment = hardware_environment()
    for kind in environment.supported_boards:
        with contextlib.suppress(Exception):  # a kind not plugged in, or failing: the others
            await environment.get_board_group(kind)
    await make_all_safe_uncancellably()
    for board in {*Board.BOARDS, *open_boards()}:
        with contextlib.suppress(Exception):
            board.close_now()


class _Watch:
    """What the supervisor knows of the match, from the program's reports."""

    def __init__(self) -> None:
        self.ends_at: float | None = None
        self.safe = False
        #: The program's run log, if it keeps one.
        self.log: str | None = None
        self._buffer = b""

    def deadline(self) -> float | None:
        """When the supervisor must end the program's process group (``None``: no match)."""
        if self.ends_at is None:
            return None
        return self.ends_at + (GROUP_WAIT if self.safe else SAFE_WAIT)

    def feed(self, data: bytes) -> None:
        self._buffer += data
        *lines, self._buffer = self._buffer.split(b"\n")
        for line in lines:
            word, _, rest = line.decode(errors="replace").partition(" ")
            if word == "start":
                with contextlib.suppress(ValueError):
                    self.ends_at = float(rest)
            elif word == "safe":
                self.safe = True
            elif word == "log" and rest:
                self.log = rest


def supervise(
    command: Sequence[str],
    *,
    environment: str | None = None,
    make_safe: Callable[[str | None], None] = make_boards_safe,
    prepare: Callable[[str | None], None] = prepare_boards_safe,
    say: Callable[[str], None] | None = None,
) -> int:
    """Run ``command`` (a supervised program) and end its match from outside it.

    :param command: the program's command line (it finds its pipe in
        :data:`SUPERVISOR_FD_VARIABLE`).
    :param environment: the program's environment name, for :func:`make_boards_safe`.
    :param make_safe: makes the boards safe after the program was ended (tests replace it).
    :param prepare: loads what ``make_safe`` needs, while the program starts.
    :param say: prints a line for the user (standard error by default).
    :returns: the exit status: the program's own, or 0 after game over.
    """
    tell = say or _say
    read_end, write_end = os.pipe()
    env = dict(os.environ)
    env[SUPERVISOR_FD_VARIABLE] = str(write_end)
    try:
        child = subprocess.Popen(
            list(command), pass_fds=[write_end], env=env, start_new_session=True
        )
    finally:
        os.close(write_end)
    previous = _forward_signals(child.pid)
    try:
        try:
            prepare(environment)
        except Exception as error:  # making safe at the end will try (and say) again
            tell(f"j5aio: could not prepare to make the boards safe: {error!r}")
        return _watch(child, read_end, environment, make_safe, tell)
    finally:
        os.close(read_end)
        for signum, handler in previous.items():
            with contextlib.suppress(ValueError, OSError):
                signal.signal(signum, handler)


def _watch(
    child: subprocess.Popen[bytes],
    read_end: int,
    environment: str | None,
    make_safe: Callable[[str | None], None],
    tell: Callable[[str], None],
) -> int:
    watch = _Watch()
    pipe_open = True
    killed_at: float | None = None
    while True:
        status = child.poll()
        now = time.monotonic()
        if status is not None:
            _end_group(child.pid)  # a forked child outlives no program
            if watch.ends_at is not None and now >= watch.ends_at:
                return 0  # game over ended it (in the program, or here)
            return status if status >= 0 else 128 - status
        deadline = watch.deadline() if killed_at is None else None
        if deadline is not None and now >= deadline:
            assert watch.ends_at is not None
            killed_at = now
            _end_group(child.pid)
            if not watch.safe:
                make_safe(environment)
                line = (
                    f"Game over: the program did not stop its boards in time; its "
                    f"processes were ended {1000 * (killed_at - watch.ends_at):.0f} ms "
                    "after the end and every board is safe."
                )
                tell(line)
                _append_to_log(watch.log, line)
            continue
        if killed_at is not None:
            timeout = 0.01  # ended: only waiting for the kernel to say so
        elif deadline is not None:
            timeout = min(deadline - now, 0.2)
        else:
            timeout = 0.2
        if pipe_open:
            ready, _, _ = _select(read_end, timeout)
            if ready:
                data = os.read(read_end, 4096)
                if data:
                    watch.feed(data)
                else:
                    pipe_open = False  # every holder closed it: the child's end is near
        else:
            with contextlib.suppress(subprocess.TimeoutExpired):
                child.wait(timeout)


def _append_to_log(path: str | None, line: str) -> None:
    """Add the supervisor's line to the program's run log (if it keeps one)."""
    if path is None:
        return
    try:
        with open(path, "a", encoding="utf-8") as log:
            log.write(f"{time.strftime('%H:%M:%S')} [supervisor] {line}\n")
    except OSError as error:
        _say(f"j5aio: could not add to the run log {path}: {error}")


def _select(fd: int, timeout: float) -> tuple[list[int], list[int], list[int]]:
    try:
        return select.select([fd], [], [], timeout)
    except InterruptedError:  # pragma: no cover - Python retries select itself (PEP 475)
        return [], [], []


def _end_group(pgid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, signal.SIGKILL)


def _forward_signals(pgid: int) -> dict[int, signal.Handlers | Callable[..., object] | int | None]:
    """Pass Ctrl-C, SIGTERM and SIGHUP on to the program's process group."""

    def forward(signum: int, frame: FrameType | None) -> None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(pgid, signum)

    previous: dict[int, signal.Handlers | Callable[..., object] | int | None] = {}
    for name in ("SIGINT", "SIGTERM", "SIGHUP"):
        signum = getattr(signal, name)
        with contextlib.suppress(ValueError, OSError):
            previous[signum] = signal.signal(signum, forward)
    return previous


def _say(line: str) -> None:
    print(line, file=sys.stderr, flush=True)
