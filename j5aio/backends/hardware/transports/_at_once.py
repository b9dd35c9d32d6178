"""Calls that block on hardware and not on the simulated kit: run in a thread only if need be.

Scanning the USB bus, listing serial ports and a pyusb device's transfers block, so they
run on a worker thread. A stand-in that answers at once (a board simulator, the simulated
kit's finder and port list) says so with a true ``answers_at_once`` attribute, and is
called in the event loop instead: a simulated start then starts no thread.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Final, TypeVar

import anyio.to_thread

__all__ = ["ANSWERS_AT_ONCE", "answers_at_once", "call_blocking", "mark_answers_at_once"]

#: The attribute by which a device, or a USB finder, says that it answers at once: a
#: simulator, whose calls are function calls that never block (see :func:`answers_at_once`).
ANSWERS_AT_ONCE: Final = "answers_at_once"

T = TypeVar("T")
F = TypeVar("F", bound=Callable[..., object])


def answers_at_once(thing: object) -> bool:
    """Whether ``thing`` (a device, or a function that finds devices) never blocks.

    It says so with a true ``answers_at_once`` attribute (``ANSWERS_AT_ONCE``: a board
    simulator, the simulated kit's finder); a pyusb device and ``usb.core.find`` have none,
    and are run on a thread. Such a device's link needs no worker thread for its transfers (see the
    USB link's notes).
    """
    return getattr(thing, ANSWERS_AT_ONCE, False) is True


def mark_answers_at_once(function: F) -> F:
    """Say that ``function`` never blocks (see :func:`answers_at_once`); return it."""
    setattr(function, ANSWERS_AT_ONCE, True)
    return function


async def call_blocking(function: Callable[..., T], *args: object, worker: object = None) -> T:
    """``function(*args)``: in the event loop if ``worker`` answers at once, else on a thread.

    :param worker: what does the blocking part (the finder or port list that ``function``
        calls); ``function`` itself if ``None``.
    """
    if answers_at_once(function if worker is None else worker):
        return function(*args)
    return await anyio.to_thread.run_sync(function, *args)
