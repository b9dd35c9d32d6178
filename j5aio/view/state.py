"""The observer that feeds the live view: the latest value of everything the program did.

:class:`ViewState` is a :data:`~j5aio.backends.backend.CallObserver`. Each interface call
of every backend is stored under what it is about (the newest replaces the older), so
however often the program calls, what waits to be sent is bounded by the number of values
on the kit. The
web server reads the values changed since it last looked, at most 20 times a second.

The observer runs in the program's event-loop thread and only stores the call; the web
server's thread turns stored calls into values when a page asks. A lock guards the
shared tables; the observer holds it for two dictionary operations.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Final

from j5aio.backends.backend import Backend
from j5aio.backends.hardware.transports.trace import TRACE, WIRE_LOGGER_PREFIX
from j5aio.boards.board import Board
from j5aio.errors import CommunicationError

from .describe import (
    ComponentInfo,
    board_components,
    component_id,
    component_names,
    describe_call,
)

__all__ = ["WIRE_LOG_LINES", "BoardRecord", "Changes", "ViewState"]

#: How many wire-log lines the view keeps (all boards together); older lines are dropped.
WIRE_LOG_LINES: Final = 2000

# Whether each interface method writes (its last argument is the value), worked out once.
_WRITES: dict[str, bool] = {}


@dataclass
class BoardRecord:
    """What the view knows of one board."""

    board: Board
    components: list[ComponentInfo]
    closed: bool = False
    known: set[ComponentInfo] = field(default_factory=set)
    #: The names of the components that are board properties of their own ("start LED").
    names: dict[ComponentInfo, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.known.update(self.components)


@dataclass
class Changes:
    """What changed since a reader last looked: values, wire-log lines, and where to go on."""

    values: list[tuple[str, str, Any]] = field(default_factory=list)
    log: list[tuple[str, str]] = field(default_factory=list)
    value_mark: int = 0
    log_mark: int = 0
    dropped_log_lines: int = 0


class ViewState:
    """The values the view shows, fed by every backend's calls and the wire loggers."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._seq = itertools.count(1)
        self._last_seq = 0
        self._values: dict[tuple[str, str], tuple[int, Any]] = {}
        #: The event loop of the latest board call: the program's (``None`` before a call).
        self.loop: asyncio.AbstractEventLoop | None = None
        self._calls: dict[tuple[Backend, str, tuple[Any, ...]], tuple[tuple[Any, ...], Any]] = {}
        self._errors: dict[Backend, str] = {}
        self._records: dict[str, BoardRecord] = {}
        self._by_backend: dict[Backend, BoardRecord] = {}
        self._log: deque[tuple[int, str, str]] = deque(maxlen=WIRE_LOG_LINES)
        self._log_seq = 0
        self._log_handler = _WireHandler(self)
        self._log_users = 0
        self._saved_level: int | None = None
        self._saved_propagate = True

    # --- fed from the program's thread ---

    def __call__(
        self,
        backend: Backend,
        method_name: str,
        arguments: tuple[Any, ...],
        result: Any,
        error: BaseException | None,
    ) -> None:
        """Take note of one interface call (the :data:`CallObserver` signature).

        Only the call is stored here, keyed so that a newer call to the same thing replaces
        the older one; it becomes a value when a page asks (:meth:`changes`), so a program
        nobody watches pays for a dictionary store and no more.
        """
        self.loop = asyncio.get_running_loop()  # where the boards live (for controls)
        if error is not None:
            if isinstance(error, CommunicationError):
                self._errors[backend] = str(error) or type(error).__name__
            return
        if self._errors:
            self._errors.pop(backend, None)
        writes = _WRITES.get(method_name)
        if writes is None:
            writes = _WRITES[method_name] = method_name.startswith(("set_", "write_"))
        key = (backend, method_name, arguments[:-1] if writes else arguments)
        try:
            with self._lock:
                self._calls.pop(key, None)  # the newest call goes last
                self._calls[key] = (arguments, result)
        except TypeError:  # an unhashable argument: a call the view cannot key
            return

    def error_of(self, board: Board) -> str | None:
        """The error of the board's last call, if it was a link error (else ``None``)."""
        return self._errors.get(board.backend)

    def _digest(self) -> None:
        """Turn the calls stored since last time into values (in the server's thread)."""
        with self._lock:
            calls, self._calls = self._calls, {}
        for (backend, method_name, _), (arguments, result) in calls.items():
            record = self._by_backend.get(backend) or self._find(backend)
            if record is None:
                continue
            board = record.board
            update = describe_call(board, method_name, arguments, result, record.components)
            if update is None:
                continue
            info = ComponentInfo(update.kind, update.identifier)
            if info not in record.known:
                record.known.add(info)
                record.components = [*record.components, info]
            key = (component_id(board.serial_number, info), update.field)
            with self._lock:
                seq = next(self._seq)
                self._values[key] = (seq, update.value)
                self._last_seq = seq

    def _find(self, backend: Backend) -> BoardRecord | None:
        for board in list(Board.BOARDS):
            if board.backend is backend:
                return self._add(board)
        return None

    def _add(self, board: Board) -> BoardRecord:
        record = self._records.get(board.serial_number)
        if record is None or record.board is not board:
            record = BoardRecord(board, board_components(board), names=component_names(board))
            self._records[board.serial_number] = record
        record.closed = False
        self._by_backend[board.backend] = record
        return record

    def add_log_line(self, port: str, text: str) -> None:
        """Keep one wire-log line of ``port``."""
        with self._lock:
            self._log_seq += 1
            self._log.append((self._log_seq, port, text))

    # --- read from the server's thread ---

    def boards(self) -> list[BoardRecord]:
        """Every board set up now or before, in serial-number order (closed ones marked)."""
        current = list(Board.BOARDS)
        for board in current:
            if self._records.get(board.serial_number, None) is None or (
                self._records[board.serial_number].board is not board
            ):
                self._add(board)
        alive = {id(board) for board in current}
        for record in self._records.values():
            record.closed = id(record.board) not in alive
        return [self._records[serial] for serial in sorted(self._records)]

    def changes(self, value_mark: int, log_mark: int) -> Changes:
        """Every value stored after ``value_mark`` and wire-log line after ``log_mark``."""
        self._digest()
        with self._lock:
            if self._last_seq > value_mark:
                # In the order they were stored: a page applies them in turn, so the newer
                # of two fields of one component (a LED's mode, then its state) wins.
                fresh = sorted(
                    (seq, cid, name, value)
                    for (cid, name), (seq, value) in self._values.items()
                    if seq > value_mark
                )
                values = [(cid, name, value) for _, cid, name, value in fresh]
            else:
                values = []
            lines = [(port, text) for seq, port, text in self._log if seq > log_mark]
            oldest = self._log[0][0] if self._log else self._log_seq + 1
            dropped = max(0, oldest - log_mark - 1) if log_mark < self._log_seq else 0
            return Changes(values, lines, self._last_seq, self._log_seq, dropped)

    # --- the wire log is recorded only while somebody watches ---

    def watch_wire(self) -> None:
        """Start recording the wire loggers' TRACE lines (one more watcher)."""
        with self._lock:
            self._log_users += 1
            if self._log_users > 1:
                return
        logger = logging.getLogger(WIRE_LOGGER_PREFIX)
        self._saved_level = logger.level
        self._saved_propagate = logger.propagate
        if not logger.isEnabledFor(TRACE):
            # The program did not ask for the wire traffic: show it on the page only.
            logger.setLevel(TRACE)
            logger.propagate = False
        logger.addHandler(self._log_handler)

    def unwatch_wire(self) -> None:
        """One watcher fewer: stop recording when there is none."""
        with self._lock:
            self._log_users -= 1
            if self._log_users > 0:
                return
        logger = logging.getLogger(WIRE_LOGGER_PREFIX)
        logger.removeHandler(self._log_handler)
        if self._saved_level is not None:
            logger.setLevel(self._saved_level)
            logger.propagate = self._saved_propagate
            self._saved_level = None


class _WireHandler(logging.Handler):
    def __init__(self, state: ViewState) -> None:
        super().__init__(TRACE)
        self._state = state

    def emit(self, record: logging.LogRecord) -> None:
        port = record.name[len(WIRE_LOGGER_PREFIX) + 1 :]
        stamp = time.strftime("%H:%M:%S", time.localtime(record.created))
        self._state.add_log_line(port, f"{stamp}.{int(record.msecs):03d} {record.getMessage()}")
