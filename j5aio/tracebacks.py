"""Short tracebacks for a student's program: the frames that are j5aio's own are left out.

``python -m j5aio run program.py`` runs the program through :func:`run_program`. When the
program stops with an exception, the traceback shows the student's lines and the error,
as pytest does, not the thirty lines of runpy, the sync facade's portal and the board
code under them. One line says how many frames were hidden and how to see them all
(``J5AIO_FULL_TRACEBACK=1``), for a bug report.

Python 3.12 and later print "Did you mean: 'buzz'?" under a misspelt attribute or name
by themselves. Python 3.11 does so only in its own last-chance handler, which a program
run through ``python -m j5aio run`` never reaches; there :func:`suggestion` adds the same
hint, so a student sees it however the program is started.
"""

from __future__ import annotations

import os
import runpy
import sys
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Final, TextIO

__all__ = [
    "FULL_TRACEBACK_VARIABLE",
    "add_hint",
    "format_trimmed",
    "is_ours",
    "run_program",
    "suggestion",
]

#: Set this environment variable (to anything but empty or ``0``) to keep every frame.
FULL_TRACEBACK_VARIABLE: Final = "J5AIO_FULL_TRACEBACK"

_PACKAGE: Final = str(Path(__file__).resolve().parent) + os.sep
_RUNPY: Final = str(Path(runpy.__file__).resolve())
#: Whether the traceback module adds "Did you mean" hints itself (Python 3.12 on).
_TRACEBACK_SUGGESTS: Final = sys.version_info >= (3, 12)
#: Names longer than this, or more candidates than this, are not looked at (as CPython).
_MAX_NAME_LENGTH: Final = 40
_MAX_CANDIDATES: Final = 750


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


def _edit_distance(first: str, second: str) -> int:
    """How many single-character edits turn ``first`` into ``second`` (a case change: 1)."""
    previous = list(range(len(second) + 1))
    for i, char in enumerate(first, 1):
        current = [i]
        for j, other in enumerate(second, 1):
            cost = 0 if char == other else 1
            current.append(min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost))
        previous = current
    return previous[-1]


def _closest(name: str, candidates: list[str]) -> str | None:
    """The candidate nearest ``name``, if it is near enough to be a slip of the keyboard."""
    if len(name) > _MAX_NAME_LENGTH or len(candidates) > _MAX_CANDIDATES:
        return None
    best: str | None = None
    best_distance = 0
    for candidate in candidates:
        if candidate == name or len(candidate) > _MAX_NAME_LENGTH:
            continue
        # A leading underscore is a private name: only suggested for a private name.
        if candidate.startswith("_") and not name.startswith("_"):
            continue
        allowed = (len(name) + len(candidate) + 3) // 6
        distance = _edit_distance(name, candidate)
        if distance <= max(allowed, 1) and (best is None or distance < best_distance):
            best, best_distance = candidate, distance
    return best


def suggestion(error: BaseException) -> str | None:
    """The name ``error`` probably meant, for a misspelt attribute or name; else ``None``.

    An :class:`AttributeError` is compared with the object's attributes, a
    :class:`NameError` with the names visible where it was raised (local, global and
    built-in).
    """
    name = getattr(error, "name", None)
    if not isinstance(name, str):
        return None
    if isinstance(error, AttributeError):
        try:
            candidates = dir(error.obj)
        except Exception:  # an object whose __dir__ fails gets no hint
            return None
        return _closest(name, candidates)
    if isinstance(error, NameError):
        frame = error.__traceback__
        while frame is not None and frame.tb_next is not None:
            frame = frame.tb_next
        if frame is None:
            return None
        scope = frame.tb_frame
        candidates = [*scope.f_locals, *scope.f_globals, *scope.f_builtins]
        return _closest(name, list(dict.fromkeys(candidates)))
    return None


def _with_suggestion(text: str, error: BaseException) -> str:
    """Add "Did you mean" to the error's own line of ``text``, where Python would."""
    if _TRACEBACK_SUGGESTS:
        return text
    meant = suggestion(error)
    if meant is None:
        return text
    line = "".join(traceback.format_exception_only(type(error), error)).rstrip("\n")
    head, found, tail = text.rpartition(line)
    if not found:
        return text
    return f"{head}{line}. Did you mean: {meant!r}?{tail}"


def format_trimmed(error: BaseException) -> str:
    """The traceback of ``error`` without j5aio's and runpy's frames, with a note of them."""
    summary = traceback.TracebackException.from_exception(error)
    hidden = _trim(summary)
    text = _with_suggestion("".join(summary.format()), error)
    if hidden:
        text += (
            f"({hidden} frame{'s' if hidden != 1 else ''} inside j5aio hidden; "
            f"set {FULL_TRACEBACK_VARIABLE}=1 to see them)\n"
        )
    return text


#: Functions that may give one more line under an uncaught error (see :func:`add_hint`).
_hints: list[Callable[[BaseException], str | None]] = []


def add_hint(hint: Callable[[BaseException], str | None]) -> None:
    """Print ``hint(error)``, unless it is ``None``, under a program's uncaught ``error``.

    For advice that only the command line knows (``run --api`` names it for a program
    that imports a competition's package that is not installed).
    """
    if hint not in _hints:
        _hints.append(hint)


def _with_hints(text: str, error: BaseException) -> str:
    for hint in _hints:
        line = hint(error)
        if line:
            text += f"{line}\n"
    return text


def _want_full() -> bool:
    return os.environ.get(FULL_TRACEBACK_VARIABLE, "").strip() not in ("", "0")


def run_program(program: Path, *, stderr: TextIO | None = None) -> int:
    """Run ``program`` as ``__main__``; on an exception print a trimmed traceback, return 1.

    An exception after the match has ended (a board closed at game over) is no error:
    the match timer ends the process with status 0, and this waits for it.

    ``SystemExit`` and ``KeyboardInterrupt`` pass through unchanged.
    """
    try:
        runpy.run_path(str(program), run_name="__main__")
    except Exception as error:
        from j5aio.safety.registry import wait_for_game_over

        if wait_for_game_over():
            return 0  # the match ended under the program: game over ends the process
        out = stderr if stderr is not None else sys.stderr
        if _want_full():
            text = _with_suggestion("".join(traceback.format_exception(error)), error)
        else:
            text = format_trimmed(error)
        print(_with_hints(text, error), end="", file=out)
        return 1
    return 0
