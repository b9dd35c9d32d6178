"""Reading lines from standard input without blocking the event loop.

``input()`` blocks its thread until the user presses return, so a console prompt reads it
in a worker thread. That alone is not enough: a prompt that is cancelled leaves its
thread blocked in ``input()``, and the line the user types next would be swallowed by
that abandoned thread. :class:`LineReader` avoids this. It keeps at most one thread
reading the stream, hands each line to the longest-waiting reader, and keeps a line
whose reader went away for the next one. So no line is lost, and lines are never read
ahead of need.
"""

from __future__ import annotations

import sys
import threading
from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from typing import TextIO

import anyio
import anyio.to_thread

__all__ = ["STDIN", "LineReader", "read_stdin_line"]


class LineReader:
    """Lines from a text stream, read in a background thread only when someone waits.

    :param stream: returns the stream to read; looked up at each read, so that a
        replaced ``sys.stdin`` is honoured. Standard input by default.
    """

    def __init__(self, stream: Callable[[], TextIO] = lambda: sys.stdin) -> None:
        self._stream = stream
        self._mutex = threading.Lock()
        self._waiting: deque[Future[str]] = deque()
        self._spare: deque[str] = deque()
        self._reading = False
        self._at_end = False

    async def readline(self) -> str:
        """Return the next line of the stream, without its line ending.

        Other tasks run while this waits, and the wait can be cancelled; a line that
        arrives after its reader was cancelled goes to the next reader.

        :raises EOFError: the stream has ended.
        """
        waiter = self._take_or_wait()
        if isinstance(waiter, str):
            return waiter
        try:
            return await anyio.to_thread.run_sync(waiter.result, abandon_on_cancel=True)
        except BaseException:
            self._withdraw(waiter)
            raise

    def _take_or_wait(self) -> str | Future[str]:
        with self._mutex:
            if self._spare:
                return self._spare.popleft()
            if self._at_end:
                raise EOFError("end of file")
            waiter: Future[str] = Future()
            self._waiting.append(waiter)
            if not self._reading:
                self._reading = True
                threading.Thread(
                    target=self._read_lines, name="j5aio-console-input", daemon=True,
                ).start()
            return waiter

    def _withdraw(self, waiter: Future[str]) -> None:
        """Take back a waiter whose reader stopped waiting; keep its line if one came."""
        with self._mutex:
            if waiter.cancel():
                self._waiting.remove(waiter)
            elif waiter.exception() is None:
                self._spare.appendleft(waiter.result())

    def _read_lines(self) -> None:
        """Read lines while readers wait (runs in the reader thread)."""
        while True:
            ending: EOFError | None
            try:
                raw = self._stream().readline()
            except (OSError, ValueError) as exc:  # a closed or broken stream ends input
                ending = EOFError(f"the input stream failed: {exc}")
            else:
                ending = None if raw else EOFError("end of file")
            with self._mutex:
                if ending is not None:
                    self._at_end = True
                    self._reading = False
                    while self._waiting:
                        waiter = self._waiting.popleft()
                        if waiter.set_running_or_notify_cancel():
                            waiter.set_exception(ending)
                    return
                self._deliver(raw.rstrip("\r\n"))
                if not self._waiting:
                    self._reading = False
                    return

    def _deliver(self, line: str) -> None:
        while self._waiting:
            waiter = self._waiting.popleft()
            if waiter.set_running_or_notify_cancel():
                waiter.set_result(line)
                return
        self._spare.append(line)


STDIN = LineReader()
"""The reader of the process's standard input, shared by every console."""


async def read_stdin_line(prompt: str) -> str:
    """Show ``prompt`` on standard output and return the next line of standard input.

    The event loop keeps running while the user types.

    :raises EOFError: standard input has ended.
    """
    sys.stdout.write(prompt)
    sys.stdout.flush()
    return await STDIN.readline()
