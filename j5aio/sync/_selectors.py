"""The portal loop's selectors: hooks around every wait, and parking on a lock.

:class:`HookedSelector` uses only the public selector interface: an asyncio selector
loop made on it calls :attr:`~HookedSelector.before_wait` each time it is about to
wait and :attr:`~HookedSelector.after_wait` each time it returns. The portal releases
the callers of finished calls in the first (just before the loop thread gives up the
GIL, so that a woken caller does not wait for the GIL too) and hands a queued call to
its worker in the second.

:class:`ParkingSelector` adds a cheaper sleep while the loop watches no file of its
own (true of the simulated kit, whose boards talk through memory): it waits on a
:class:`threading.Lock`, one futex wake, instead of a socket write, a return from
``epoll`` and a socket read. A loop that sleeps on a lock must hear of *every* wake-up
from another thread (``call_soon_threadsafe``), and asyncio sends those through a
private method, ``_write_to_self``; :class:`ParkingLoop` hooks it. Where that method
is missing (:data:`CAN_PARK` is false, as on Windows or on a Python that renamed it),
the portal uses a plain event loop instead, which its tests run as well.
"""

from __future__ import annotations

import asyncio
import selectors
import sys
import threading
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any, Final

from j5aio.sync._calls import new_done_lock

if TYPE_CHECKING:
    from _typeshed import FileDescriptorLike

__all__ = ["CAN_PARK", "HookedSelector", "ParkingLoop", "ParkingSelector"]


def _nothing() -> None:
    """Do nothing (the default hook)."""


class HookedSelector(selectors.BaseSelector):
    """The default selector, with a hook before and after every wait."""

    def __init__(self) -> None:
        self._inner = selectors.DefaultSelector()
        self.before_wait: Callable[[], None] = _nothing
        self.after_wait: Callable[[], None] = _nothing

    def register(
        self, fileobj: FileDescriptorLike, events: int, data: Any = None
    ) -> selectors.SelectorKey:
        """Watch ``fileobj`` (as :meth:`selectors.BaseSelector.register`)."""
        return self._inner.register(fileobj, events, data)

    def unregister(self, fileobj: FileDescriptorLike) -> selectors.SelectorKey:
        """Stop watching ``fileobj`` (as :meth:`selectors.BaseSelector.unregister`)."""
        return self._inner.unregister(fileobj)

    def modify(
        self, fileobj: FileDescriptorLike, events: int, data: Any = None
    ) -> selectors.SelectorKey:
        """Change what is watched on ``fileobj`` (as :meth:`selectors.BaseSelector.modify`)."""
        return self._inner.modify(fileobj, events, data)

    def get_map(self) -> Mapping[FileDescriptorLike, selectors.SelectorKey]:
        """Return the watched files (as :meth:`selectors.BaseSelector.get_map`)."""
        return self._inner.get_map()

    def close(self) -> None:
        """Close the inner selector."""
        self._inner.close()

    def select(
        self, timeout: float | None = None
    ) -> list[tuple[selectors.SelectorKey, int]]:
        """Wait up to ``timeout`` seconds for files, running the hooks around the wait."""
        self.before_wait()
        try:
            return self._wait(timeout)
        finally:
            self.after_wait()

    def _wait(self, timeout: float | None) -> list[tuple[selectors.SelectorKey, int]]:
        return self._inner.select(timeout)


class ParkingSelector(HookedSelector):
    """A hooked selector whose loop sleeps on a lock while it watches no file descriptor.

    :meth:`ring` wakes the loop the cheap way when it is parked on the lock, and through
    the loop's self-pipe (``write_to_pipe``) when it is in ``epoll``.
    """

    _AWAKE: Final = 0
    _PARKED: Final = 1
    _IN_EPOLL: Final = 2

    def __init__(self) -> None:
        super().__init__()
        self._mutex = threading.Lock()
        self._bell = new_done_lock()
        self._mode = self._AWAKE
        self._rung = False
        self.own_files = 1  # the loop's self-pipe, which a parked loop need not watch
        self.write_to_pipe: Callable[[], None] = _nothing

    def _wait(self, timeout: float | None) -> list[tuple[selectors.SelectorKey, int]]:
        if len(self._inner.get_map()) > self.own_files:
            return self._select_files(timeout)
        if timeout is None or timeout > 0:
            self._park(timeout)
        else:
            self._rung = False
        return []

    def _select_files(
        self, timeout: float | None
    ) -> list[tuple[selectors.SelectorKey, int]]:
        with self._mutex:
            if self._rung:
                self._rung = False
                timeout = 0
            self._mode = self._IN_EPOLL
        try:
            return self._inner.select(timeout)
        finally:
            with self._mutex:
                self._mode = self._AWAKE
                self._rung = False

    def _park(self, timeout: float | None) -> None:
        with self._mutex:
            if self._rung:
                self._rung = False
                return
            self._mode = self._PARKED
        bell = self._bell
        bell.acquire(True, -1 if timeout is None else min(timeout, threading.TIMEOUT_MAX))
        with self._mutex:
            self._mode = self._AWAKE
            self._rung = False
            bell.acquire(False)  # a ring that came after a timeout: the bell stays held

    def ring(self) -> None:
        """Wake the loop, or make its next wait return at once (from any thread)."""
        with self._mutex:
            self._rung = True
            mode = self._mode
            if mode == self._PARKED:
                self._mode = self._AWAKE
                self._bell.release()
                return
        if mode == self._IN_EPOLL:
            self.write_to_pipe()


class ParkingLoop(asyncio.SelectorEventLoop):
    """An asyncio selector loop on a :class:`ParkingSelector`, woken through its bell."""

    def __init__(self, selector: ParkingSelector) -> None:
        selector.write_to_pipe = super()._write_to_self  # type: ignore[misc]
        super().__init__(selector)
        self.parking = selector

    def _write_to_self(self) -> None:
        # Every wake-up from another thread (call_soon_threadsafe) comes through here.
        self.parking.ring()


#: Whether the portal's loop can park on a lock: asyncio's selector loop on POSIX, as long
#: as it still wakes itself through ``_write_to_self`` (true of Python 3.11 to 3.14).
CAN_PARK: Final = sys.platform != "win32" and hasattr(
    asyncio.selector_events.BaseSelectorEventLoop, "_write_to_self"
)
