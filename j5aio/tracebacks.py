"""Short tracebacks for a student's program: the frames that are j5aio's own are left out.

``python -m j5aio run program.py`` runs the program through :func:`run_program`. When the
program stops with an exception, the traceback shows the student's lines and the error,
as pytest does, not the thirty lines of runpy, the sync facade's portal and the board
code under them. One line says how many frames were hidden and how to see them all
(``J5AIO_FULL_TRACEBACK=1``), for a bug report.
"""

from __future__ import annotations

import os
import runpy
import sys
import traceback
from pathlib import Path
from typing import Final, TextIO

__all__ = ["FULL_TRACEBACK_VARIABLE", "format_trimmed", "is_ours", "run_program"]

#: Set this environment variable (to anything but empty or ``0``) to keep every frame.
FULL_TRACEBACK_VARIABLE: Final = "J5AIO_FULL_TRACEBACK"

_PACKAGE: Final = str(Path(__file__).resolve().parent) + os.sep
_RUNPY: Final = str(Path(runpy.__file__).resolve())


def is_ours(filename: str) -> bool:
    """Whether a frame in ``filename`` is j5aio's or runpy's, not the program's."""
    if filename.startswith("<frozen runpy"):
        return True
    try:
        resolved = str(Path(filename).resolve())
    except (OSError, ValueError):  # pragma: no cover - a name such as "<string>"
        return False
    return resolved.startswith(_PACKAGE) or resolved == _RUNPY


def _trim(summary: traceback.TracebackException) -> int:
    """Drop our frames from ``summary`` and its causes, in place; return how many went.

    A ``TracebackException`` is a tree (it breaks the cycles of the exceptions it
    describes), so each node is visited once.
    """
    kept = [frame for frame in summary.stack if not is_ours(frame.filename)]
    hidden = len(summary.stack) - len(kept)
    summary.stack = traceback.StackSummary.from_list(kept)
    for linked in (summary.__cause__, summary.__context__):
        if linked is not None:
            hidden += _trim(linked)
    for member in getattr(summary, "exceptions", None) or ():
        hidden += _trim(member)
    return hidden


def format_trimmed(error: BaseException) -> str:
    """The traceback of ``error`` without j5aio's and runpy's frames, with a note of them."""
    summary = traceback.TracebackException.from_exception(error)
    hidden = _trim(summary)
    text = "".join(summary.format())
    if hidden:
        text += (
            f"({hidden} frame{'s' if hidden != 1 else ''} inside j5aio hidden; "
            f"set {FULL_TRACEBACK_VARIABLE}=1 to see them)\n"
        )
    return text


def _want_full() -> bool:
    return os.environ.get(FULL_TRACEBACK_VARIABLE, "").strip() not in ("", "0")


def run_program(program: Path, *, stderr: TextIO | None = None) -> int:
    """Run ``program`` as ``__main__``; on an exception print a trimmed traceback, return 1.

    ``SystemExit`` and ``KeyboardInterrupt`` pass through unchanged.
    """
    try:
        runpy.run_path(str(program), run_name="__main__")
    except Exception as error:
        out = stderr if stderr is not None else sys.stderr
        if _want_full():
            traceback.print_exception(error, file=out)
        else:
            print(format_trimmed(error), end="", file=out)
        return 1
    return 0
