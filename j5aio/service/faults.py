"""Saying what went wrong with the service once, not at every message or every retry."""

from __future__ import annotations

import logging
import threading

__all__ = ["FaultLog"]


class FaultLog:
    """Logs each kind of fault at ``level`` the first time, and at DEBUG after that.

    A broker that sends the same bad message every second, or that stays away for the
    whole match, gives one line in the log, not thousands. :meth:`forget` makes a kind
    worth saying again (e.g. "cannot connect" once the connection has come back).
    """

    def __init__(self, logger: logging.Logger, level: int = logging.WARNING) -> None:
        self._logger = logger
        self._level = level
        self._seen: set[str | tuple[str, str]] = set()
        self._lock = threading.Lock()

    def report(self, kind: str | tuple[str, str], message: str, *args: object) -> bool:
        """Log ``message % args``; loudly only the first time ``kind`` is reported.

        :returns: whether this was the first time.
        """
        with self._lock:
            first = kind not in self._seen
            self._seen.add(kind)
        self._logger.log(self._level if first else logging.DEBUG, message, *args)
        return first

    def forget(self, kind: str | tuple[str, str]) -> None:
        """Let the next report of ``kind`` be logged loudly again."""
        with self._lock:
            self._seen.discard(kind)

    def seen(self, kind: str | tuple[str, str]) -> bool:
        """Whether ``kind`` has been reported (and not forgotten)."""
        with self._lock:
            return kind in self._seen
