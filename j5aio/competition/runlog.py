"""Run logs: what a robot program printed, and j5aio's log, kept in a file per run.

``python -m j5aio run program.py`` copies the program's standard output and standard
error, and j5aio's log (from INFO up), to ``run-YYYYMMDD-HHMMSS.log``:

- in ``J5AIO_LOG_DIR`` if that is set;
- else in ``logs`` on the team's USB stick: the one the robot service says holds the
  team's code, else the one holding the metadata file, else the first one mounted
  (not if ``logs`` there is a link: it could lead off the stick, where rotation would
  delete files; a warning says so);
- else in ``j5aio-logs`` beside the program.

The file can be read by its owner only (where the drive keeps permissions), and the
live view's secret (``token=...`` in its address) is replaced by ``token=<hidden>``
in it: the stick is handed round on match day.

The file starts with a header (j5aio's version, Python's, the program, the metadata);
the robot adds a line per board it found (type, serial number, firmware) when it starts.

Rotation keeps a stick from filling up: before a new log is opened the oldest logs are
deleted until at most :data:`MAX_LOG_FILES` remain, they take at most
:data:`MAX_TOTAL_BYTES` together, and :data:`RESERVE_BYTES` stay free on the drive;
one log stops growing at :data:`MAX_FILE_BYTES`, with a line saying so.
"""

from __future__ import annotations

import contextlib
import logging
import os
import platform
import re
import shutil
import stat
import sys
import threading
from collections.abc import Callable, Iterator
from datetime import UTC, datetime
from pathlib import Path
from typing import Final, TextIO

from j5aio.competition.metadata import Metadata, MetadataError, describe, find_usb_sticks

__all__ = [
    "LOG_DIR_VARIABLE",
    "MAX_FILE_BYTES",
    "MAX_LOG_FILES",
    "MAX_TOTAL_BYTES",
    "RESERVE_BYTES",
    "RunLog",
    "choose_log_folder",
    "rotate",
    "teeing",
]

#: The environment variable naming the folder for run logs.
LOG_DIR_VARIABLE: Final = "J5AIO_LOG_DIR"
#: The most run logs kept in a folder (the new one included).
MAX_LOG_FILES: Final = 20
#: The most bytes all run logs of a folder may take together (before the new one).
MAX_TOTAL_BYTES: Final = 50 * 1024 * 1024
#: The most bytes one run log grows to.
MAX_FILE_BYTES: Final = 5 * 1024 * 1024
#: The bytes left free on the drive (old logs are deleted to keep them free).
RESERVE_BYTES: Final = 2 * MAX_FILE_BYTES
_PATTERN: Final = "run-*.log"
#: A live view's secret in its address (``?token=...``), hidden in run logs.
_TOKEN: Final = re.compile(r"(\btoken=)[A-Za-z0-9_\-]+")

LOGGER = logging.getLogger(__name__)


def choose_log_folder(program: Path, metadata: Metadata | None = None) -> Path:
    """Where the run log of ``program`` goes (see the module's documentation)."""
    named = os.environ.get(LOG_DIR_VARIABLE)
    if named:
        return Path(named)
    for stick in _sticks_in_order(metadata):
        folder = stick / "logs"
        if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
            LOGGER.warning(
                "Not logging to %s: it is a link or not a folder; make it a folder", folder
            )
            continue
        return folder
    return program.resolve().parent / "j5aio-logs"


def _sticks_in_order(metadata: Metadata | None) -> list[Path]:
    """The team's stick first (the service's, else the metadata's), then the others."""
    from j5aio.competition import service_state

    sticks = find_usb_sticks()
    usercode = service_state.usercode_path()
    if usercode is not None:
        return [usercode]
    if metadata is not None and metadata.source is not None and metadata.source.parent in sticks:
        return [metadata.source.parent]
    return sticks[:1]


def rotate(
    folder: Path,
    *,
    max_files: int = MAX_LOG_FILES,
    max_total: int = MAX_TOTAL_BYTES,
    reserve: int = RESERVE_BYTES,
    free_bytes: Callable[[Path], int] | None = None,
) -> list[Path]:
    """Delete the oldest run logs in ``folder`` to make room for a new one.

    :param max_files: keep at most this many, counting the new one.
    :param max_total: the old ones kept take at most this many bytes.
    :param reserve: delete old ones while fewer bytes than this are free.
    :param free_bytes: says how many bytes are free on ``folder``'s drive.
    :returns: the logs deleted.
    """
    if free_bytes is None:
        free_bytes = _free_bytes
    logs = sorted(log for log in folder.glob(_PATTERN) if _is_regular_file(log))
    sizes = {log: _size(log) for log in logs}
    deleted: list[Path] = []
    while logs and (
        len(logs) >= max_files
        or sum(sizes[log] for log in logs) > max_total
        or free_bytes(folder) < reserve
    ):
        oldest = logs.pop(0)
        with contextlib.suppress(OSError):
            oldest.unlink()
            deleted.append(oldest)
    return deleted


def _size(path: Path) -> int:
    try:
        return path.lstat().st_size
    except OSError:
        return 0


def _is_regular_file(path: Path) -> bool:
    """Whether ``path`` is a file itself (not a link to one: rotation never follows one)."""
    try:
        return stat.S_ISREG(path.lstat().st_mode)
    except OSError:
        return False


def _free_bytes(folder: Path) -> int:
    return shutil.disk_usage(folder).free


class RunLog:
    """One run's log file, written from any thread, capped at ``max_bytes``.

    :param folder: where to write it (made if need be; old logs rotated first).
    :param now: the time of the run (its name); now if omitted.
    :param max_bytes: the most bytes the file grows to.
    :raises OSError: the folder cannot be made or the file opened.
    """

    def __init__(
        self, folder: Path, *, now: datetime | None = None, max_bytes: int = MAX_FILE_BYTES
    ) -> None:
        folder.mkdir(parents=True, exist_ok=True)
        self.deleted = rotate(folder)
        stamp = (now or datetime.now(UTC)).strftime("%Y%m%d-%H%M%S")
        self.path, descriptor = _create_new(folder, stamp)
        # (a descriptor made with O_EXCL and mode 0o600; closed by close())
        self._file = os.fdopen(descriptor, "w", encoding="utf-8", errors="replace")
        self._lock = threading.Lock()
        self._written = 0
        self._max_bytes = max_bytes
        self._full = False

    def write(self, text: str) -> None:
        """Add ``text`` (until the file is full; then one line says so).

        A live view's address has its secret replaced: ``token=<hidden>``.
        """
        text = _TOKEN.sub(r"\1<hidden>", text)
        with self._lock:
            if self._full or self._file.closed:
                return
            size = len(text.encode("utf-8", errors="replace"))
            if self._written + size > self._max_bytes:
                self._full = True
                self._file.write("\n[j5aio: this log is full; the rest of the run is not kept]\n")
            else:
                self._written += size
                self._file.write(text)
            self._file.flush()

    def write_header(self, program: Path, metadata: Metadata | MetadataError) -> None:
        """Write the header: versions, program, metadata."""
        from j5aio import __version__

        facts = {
            "j5aio": __version__,
            "python": platform.python_version(),
            "program": str(program),
            "started": datetime.now(UTC).isoformat(timespec="seconds"),
            "metadata": describe(metadata)
            if isinstance(metadata, Metadata)
            else f"unusable: {metadata}",
            "kit": "one 'Kit:' line per board below, when the robot starts",
        }
        self.write("".join(f"# {key}: {value}\n" for key, value in facts.items()))
        if self.deleted:
            self.write(f"# rotated: deleted {len(self.deleted)} old log(s) to make room\n")

    def close(self) -> None:
        """Close the file."""
        with self._lock:
            self._file.close()


def _create_new(folder: Path, stamp: str) -> tuple[Path, int]:
    """Make a new log file for ``stamp``, readable by its owner only, never through a link.

    :returns: its path and an open descriptor.
    :raises OSError: it cannot be made.
    """
    flags = (
        os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
        | getattr(os, "O_CLOEXEC", 0)
    )
    number = 1
    path = folder / f"run-{stamp}.log"
    while True:
        try:
            return path, os.open(path, flags, 0o600)
        except FileExistsError:
            number += 1
            path = folder / f"run-{stamp}-{number}.log"


class _Tee:
    """A text stream that writes to its original stream and to a run log."""

    def __init__(self, original: TextIO, log: RunLog) -> None:
        self._original = original
        self._log = log

    def write(self, text: str) -> int:
        self._log.write(text)
        return self._original.write(text)

    def flush(self) -> None:
        self._original.flush()

    def __getattr__(self, name: str) -> object:
        return getattr(self._original, name)


class _LogHandler(logging.Handler):
    def __init__(self, log: RunLog) -> None:
        super().__init__(logging.INFO)
        self._log = log
        self.setFormatter(
            logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s")
        )

    def emit(self, record: logging.LogRecord) -> None:
        try:
            self._log.write(self.format(record) + "\n")
        except Exception:  # pragma: no cover - logging must never raise
            self.handleError(record)


@contextlib.contextmanager
def teeing(log: RunLog) -> Iterator[None]:
    """Copy ``sys.stdout``, ``sys.stderr`` and j5aio's log to ``log`` for a while.

    j5aio's warnings still reach the console (on the original standard error), as they
    would without a run log.
    """
    stdout, stderr = sys.stdout, sys.stderr
    sys.stdout = _Tee(stdout, log)
    sys.stderr = _Tee(stderr, log)
    j5aio_logger = logging.getLogger("j5aio")
    to_file = _LogHandler(log)
    to_console = logging.StreamHandler(stderr)
    to_console.setLevel(logging.WARNING)
    level = j5aio_logger.level
    j5aio_logger.addHandler(to_file)
    j5aio_logger.addHandler(to_console)
    if j5aio_logger.getEffectiveLevel() > logging.INFO:
        j5aio_logger.setLevel(logging.INFO)
    try:
        yield
    finally:
        j5aio_logger.removeHandler(to_file)
        j5aio_logger.removeHandler(to_console)
        j5aio_logger.setLevel(level)
        sys.stdout, sys.stderr = stdout, stderr
