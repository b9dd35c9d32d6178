"""Waiting for the start of a match: the start button, or a start from outside.

:func:`wait_for_start` returns when any of these happens:

- a start button is pressed (any board with a ``start_button``: the SR power boards;
  on the simulated kit, ``kit.power_boards[0].press_start()``);
- the *start file* appears: a competition runner on the same machine starts the robot
  with ``touch /tmp/j5aio-start`` (the path is :func:`start_file`: ``J5AIO_START_FILE``
  if set, else ``j5aio-start`` in the system's temporary directory). The file is
  local to the machine, so nothing on the network can start a robot; on the machine,
  only a regular file owned by the robot's user (or root) counts, so another user
  cannot start the robot by creating it, nor leave one behind that the robot cannot
  remove. A file that does not count is reported and ignored. The file is removed when
  the wait begins (a stale one from an earlier run does not count) and again when it
  is seen;
- :func:`trigger_start` is called in this process, from any thread: ``python -m j5aio
  run`` does so after ``--start-after`` seconds, or when Enter is pressed in its
  console; the robot service's client does so on a remote start. The waiting robot is
  woken at once (the start file is looked for every :data:`POLL_INTERVAL`).

While it waits, the run LED of every board that has one flashes, the start LED of a KCH
flashes, and every piezo gives one short beep at the beginning.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import stat
import threading
from collections.abc import Awaitable, Callable, Iterable
from datetime import timedelta
from pathlib import Path
from typing import Final, TypeVar

import anyio

from j5aio.boards.board import Board
from j5aio.components._checks import check_timeout
from j5aio.components._first import first_of
from j5aio.components.button import Button
from j5aio.components.flashing_led import FlashingLED
from j5aio.components.led import LED
from j5aio.components.piezo import Note, Piezo

__all__ = [
    "POLL_INTERVAL",
    "START_FILE_VARIABLE",
    "clear_trigger",
    "is_waiting",
    "start_file",
    "trigger_start",
    "wait_for_start",
]

LOGGER = logging.getLogger(__name__)

#: The environment variable naming the start file.
START_FILE_VARIABLE: Final = "J5AIO_START_FILE"
#: How often the start file is looked for while waiting, in seconds (the buttons are
#: waited for by their boards, which say as soon as one is pressed, and a
#: :func:`trigger_start` wakes the wait at once).
POLL_INTERVAL: Final = 0.05
#: The run LED changes every this many looks (0.3 s).
_FLASH_POLLS: Final = 6
_BEEP: Final = timedelta(milliseconds=100)

#: The pending :func:`trigger_start`: what it said started the robot, until a wait takes
#: it. Guarded by ``_trigger_lock``, as is ``_waiters``.
_trigger: str | None = None
_trigger_lock = threading.Lock()
#: The event loops of the waits under way, each with the event that wakes it.
_waiters: set[tuple[asyncio.AbstractEventLoop, asyncio.Event]] = set()


def start_file() -> Path:
    """The file whose appearance starts the robot (``J5AIO_START_FILE`` or the default)."""
    named = os.environ.get(START_FILE_VARIABLE)
    if named:
        return Path(named)
    import tempfile  # (here: it imports shutil, random and more, which a start rarely needs)

    return Path(tempfile.gettempdir()) / "j5aio-start"


def trigger_start(how: str = "trigger") -> None:
    """Start the robot waiting in :func:`wait_for_start` at once, or the next one to wait.

    Safe to call from any thread, and from the robot's own event loop.

    :param how: what started the robot, as :func:`wait_for_start` returns and logs it
        (e.g. ``"remote start"``).
    :raises TypeError: ``how`` is not text.
    """
    global _trigger
    if not isinstance(how, str):
        raise TypeError(f"how must be text saying what started the robot, not {how!r}")
    with _trigger_lock:
        _trigger = how
        waiters = list(_waiters)
    for loop, event in waiters:
        with contextlib.suppress(RuntimeError):  # that loop has closed: its wait is over
            loop.call_soon_threadsafe(event.set)


def is_waiting() -> bool:
    """Whether a :func:`wait_for_start` is waiting now, in any thread of this process.

    The robot service passes a remote start on only then, as a robot's own service does:
    a start sent while nothing waits (or left retained on the broker) starts nothing.
    """
    with _trigger_lock:
        return bool(_waiters)


def clear_trigger() -> None:
    """Forget a :func:`trigger_start` that no wait has taken yet."""
    global _trigger
    with _trigger_lock:
        _trigger = None


def _take_trigger() -> str | None:
    global _trigger
    with _trigger_lock:
        how, _trigger = _trigger, None
    return how


_T = TypeVar("_T")


def _components(boards: Iterable[Board], name: str, kind: type[_T]) -> list[_T]:
    found = (getattr(board, name, None) for board in boards)
    return [component for component in found if isinstance(component, kind)]


def _trusted_owners() -> set[int] | None:
    """The users whose start file counts: the robot's and root; ``None``: no owners here."""
    getuid = getattr(os, "getuid", None)
    return None if getuid is None else {getuid(), 0}


#: The start files already reported as refused (path, device, inode), so that a poll does
#: not log the same one every time.
_reported: set[tuple[str, int, int]] = set()


def _take_start_file(path: Path) -> bool:
    """Whether the start file is there and counts; it is removed if so.

    It counts only if it is a regular file (not a directory, nor a link) owned by the
    robot's user or root, and the robot removed it: a file the robot cannot remove
    would otherwise start every later wait at once.
    """
    try:
        info = path.lstat()
    except FileNotFoundError:
        return False
    except OSError as exc:
        _report_once(path, None, f"cannot be looked at: {exc.strerror or exc}")
        return False
    owners = _trusted_owners()
    if not stat.S_ISREG(info.st_mode):
        _report_once(path, info, "is not a regular file (a directory or a link?)")
        return False
    if owners is not None and info.st_uid not in owners:
        _report_once(
            path,
            info,
            f"belongs to another user (uid {info.st_uid}): only the robot's user or root "
            "may start it",
        )
        return False
    try:
        path.unlink()
    except FileNotFoundError:  # another wait took it first
        return False
    except OSError as exc:
        _report_once(path, info, f"cannot be removed: {exc.strerror or exc}")
        return False
    return True


def _report_once(path: Path, info: os.stat_result | None, problem: str) -> None:
    key = (str(path), info.st_dev if info else 0, info.st_ino if info else 0)
    if key not in _reported:
        _reported.add(key)
        LOGGER.error("Ignoring the start file %s: it %s. Remove it.", path, problem)


async def wait_for_start(boards: Iterable[Board], timeout: float | None = None) -> str:
    """Wait for the start (see the module's documentation), signalling on the boards.

    :param boards: the robot's boards: their start buttons, run LEDs, KCH start LEDs and
        piezos are used.
    :param timeout: give up after this many seconds; ``None`` waits for ever.
    :returns: what started the robot: ``"button"``, ``"start file"``, or what
        :func:`trigger_start` was given (``"trigger"`` unless it said otherwise).
    :raises TimeoutError: nothing started the robot within ``timeout`` seconds.
    :raises TypeError: ``timeout`` is not a number or ``None``.
    :raises ValueError: ``timeout`` is negative or NaN.
    :raises CommunicationError: a board did not answer.
    """
    limit = check_timeout(timeout)
    boards = list(boards)
    buttons = _components(boards, "start_button", Button)
    leds = _components(boards, "run_led", LED)
    # An LED that flashes by itself (a KCH's start LED, a fw 4 power board's run LED) is
    # told to; the others are switched by the wait below.
    flashing = [led for led in leds if isinstance(led, FlashingLED)]
    flashing += _components(boards, "start_led", FlashingLED)
    run_leds = [led for led in leds if not isinstance(led, FlashingLED)]
    path = start_file()
    _take_start_file(path)  # a file left from an earlier run does not count
    for button in buttons:
        await button.get_is_pressed()  # discard a press latched before the wait
    for piezo in _components(boards, "piezo", Piezo):
        await piezo.buzz(_BEEP, Note.A6)
    for flasher in flashing:
        await flasher.flash()
    LOGGER.info(
        "Waiting for the start: press the start button, or create %s", path
    )
    with anyio.fail_after(limit):
        how = _take_trigger()  # a trigger given before the wait: no board is waited on
        if how is None:
            how = await first_of(
                [
                    *(_pressed(button) for button in buttons),
                    lambda: _start_file_appears(path),
                    _triggered,
                ],
                beside=[lambda: _flash(run_leds)] if run_leds else [],
            )
    for led in leds:
        await led.set_state(True)  # the run LED: lit while the robot runs
    for flasher in flashing:
        if flasher not in leds:
            await flasher.set_state(False)  # a KCH's start LED: off once started
    LOGGER.info("Started (by the %s).", how)
    return how


def _pressed(button: Button) -> Callable[[], Awaitable[str]]:
    async def wait() -> str:
        await button.wait_until_pressed()
        return "button"

    return wait


async def _start_file_appears(path: Path) -> str:
    """Look for the start file every :data:`POLL_INTERVAL`."""
    while True:
        await anyio.sleep(POLL_INTERVAL)
        if _take_start_file(path):
            return "start file"


async def _triggered() -> str:
    """Wait for :func:`trigger_start`, woken by it from any thread."""
    waiter = (asyncio.get_running_loop(), asyncio.Event())
    with _trigger_lock:
        _waiters.add(waiter)
    try:
        while True:
            how = _take_trigger()  # after registering: a trigger before it is seen here
            if how is not None:
                return how
            await waiter[1].wait()
            waiter[1].clear()
    finally:
        with _trigger_lock:
            _waiters.discard(waiter)


async def _flash(leds: list[LED]) -> None:
    """Switch the run LEDs on and off, every ``_FLASH_POLLS`` looks, until cancelled."""
    led_on = False
    while True:
        led_on = not led_on
        for led in leds:
            await led.set_state(led_on)
        await anyio.sleep(POLL_INTERVAL * _FLASH_POLLS)
