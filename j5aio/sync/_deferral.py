"""Signals that arrive while the main thread runs the facade's event loop itself.

Python runs a signal's handler in the main thread, between two bytecodes. When the main
thread is inside a blocking call of the facade it is running the event loop's own code
(:mod:`j5aio.sync._driven`), and a handler that raises there (``KeyboardInterrupt`` on
Ctrl-C, ``SystemExit`` from the safety net's SIGTERM handler) would tear asyncio or j5aio
half way through a step. So, for SIGINT, SIGTERM and SIGHUP, the handler the program has
(whichever it is: Python's, the safety net's, the program's own) is wrapped
(:class:`DeferringHandler`, installed with the public :func:`signal.signal`):

* outside a driven call the wrapper calls the handler at once, exactly as without it;
* inside one it only records the signal and asks the loop to stop (``stop`` is given by
  the loop's owner; asyncio documents ``call_soon_threadsafe`` as safe to use from a
  signal handler, and its self-pipe wakes a loop that waits in its selector). The caller,
  back outside the loop, then runs the handler (:meth:`SignalDeferral.run_pending`): if
  it raises, the call is cancelled through its anyio cancel scope and the exception
  surfaces from the call, as it did when the caller waited on a lock.

A handler installed later (by the program, or by the safety net) is wrapped at the next
call (:meth:`SignalDeferral.install`); the wrapper names what it wraps in ``__wrapped__``.
"""

from __future__ import annotations

import contextlib
import importlib
import signal
import threading
from collections.abc import Callable
from types import FrameType
from typing import Any, Final

__all__ = ["DEFERRED_SIGNALS", "DeferringHandler", "SignalDeferral", "current_handler"]



def _find_current_handler() -> Callable[[int], Any]:
    """CPython's own ``getsignal``, or the public one where it is not there.

    The public :func:`signal.getsignal` calls the C one and turns its result into an enum
    member where it can: 1.5 us, against 12 ns, for a check made at every call.
    """
    try:
        found = importlib.import_module("_signal").getsignal
    except (ImportError, AttributeError):
        return signal.getsignal
    return found if callable(found) else signal.getsignal


#: The handler Python has for a signal now (as :func:`signal.getsignal`, only cheaper).
current_handler: Callable[[int], Any] = _find_current_handler()

#: The signals whose handlers are deferred while the main thread drives the loop.
DEFERRED_SIGNALS: Final = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

Handler = Callable[[int, FrameType | None], Any]


class DeferringHandler:
    """A signal handler that defers ``handler`` while its :class:`SignalDeferral` is active."""

    __slots__ = ("__wrapped__", "deferral")

    def __init__(self, deferral: SignalDeferral, handler: Handler) -> None:
        self.deferral = deferral
        self.__wrapped__ = handler

    def __call__(self, signum: int, frame: FrameType | None) -> Any:
        """Run the handler now, or record it for the caller to run when the loop stops."""
        deferral = self.deferral
        if deferral.active:
            deferral.pending.append((self.__wrapped__, signum, frame))
            deferral.stop()
            return None
        return self.__wrapped__(signum, frame)

    def __repr__(self) -> str:
        return f"<deferred while the sync facade drives its loop: {self.__wrapped__!r}>"


class SignalDeferral:
    """The main thread's deferred signals, for one driven event loop.

    :param stop: stops the loop the main thread drives; called from a signal handler, so
        it must be safe there (``loop.call_soon_threadsafe(loop.stop)`` is).
    """

    def __init__(self, stop: Callable[[], None]) -> None:
        self.stop = stop
        #: Whether the main thread is inside a driven call (set by the main thread only).
        self.active = False
        #: The handlers whose signals came while active, with their arguments, in order.
        self.pending: list[tuple[Handler, int, FrameType | None]] = []
        self._installed: dict[int, DeferringHandler] = {}
        #: Each deferred signal with the handler it had when last checked: a caller checks
        #: them (with :func:`current_handler`) and calls :meth:`install` if one changed.
        self.seen: tuple[tuple[int, Any], ...] = tuple((s, None) for s in DEFERRED_SIGNALS)

    def install(self) -> None:
        """Wrap each deferred signal's Python handler, unless it is wrapped already.

        Called from the main thread when :attr:`seen` is out of date. ``SIG_DFL`` and
        ``SIG_IGN`` are left alone: the operating system acts on them without Python.
        """
        installed = self._installed
        for signum in DEFERRED_SIGNALS:
            current = current_handler(signum)
            if current is installed.get(signum) or not callable(current):
                continue
            if isinstance(current, DeferringHandler):  # another loop's: wrap what it wraps
                current = current.__wrapped__
            wrapper = DeferringHandler(self, current)
            with contextlib.suppress(ValueError, OSError):
                signal.signal(signum, wrapper)
                installed[signum] = wrapper
        self.seen = tuple((signum, current_handler(signum)) for signum in DEFERRED_SIGNALS)

    def uninstall(self) -> None:
        """Put back the handlers this deferral wrapped, where they are still its wrappers."""
        if threading.current_thread() is not threading.main_thread():
            return
        for signum, wrapper in self._installed.items():
            with contextlib.suppress(ValueError, OSError):
                if signal.getsignal(signum) is wrapper:
                    signal.signal(signum, wrapper.__wrapped__)
        self._installed.clear()
        self.seen = tuple((signum, None) for signum in DEFERRED_SIGNALS)

    def run_pending(self) -> None:
        """Run the handlers of the signals recorded so far, in order (main thread).

        The first handler that raises ends the run; the signals after it are dropped, as
        Python would never have run their handlers either.
        """
        pending = self.pending
        try:
            while pending:
                handler, signum, frame = pending.pop(0)
                handler(signum, frame)
        except BaseException:
            pending.clear()
            raise
