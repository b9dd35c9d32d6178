"""How j5aio's board errors reach an sbot program, and the end of a match.

sbot raises ``BoardDisconnectionError`` (an ``IOError``) when a board stops answering;
j5aio raises its :class:`~j5aio.errors.CommunicationError`. :func:`translate_errors`
wraps the public methods of sbot's modules so that a program gets sbot's error (which
is j5aio's :class:`~j5aio.errors.BoardDisconnectionError` too, with j5aio's error as
its cause), and, once the match is over (every board is then safe and closed), a quiet
end with status 0 for whatever a call then fails with, as sbot's timeout ends a program.
"""

from __future__ import annotations

import functools
import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from j5aio.errors import CommunicationError

from .internal.exceptions import BoardDisconnectionError

if TYPE_CHECKING:
    from j5aio.competition.timer import MatchTimer

__all__ = ["end_of_match", "translate_errors", "watch_match"]

C = TypeVar("C", bound=type)

_TIMEOUT_LOGGER = logging.getLogger("sbot.internal.timeout")
_game_over = threading.Event()
_ending = threading.Lock()
_timers: list[MatchTimer] = []


def watch_match(timer: MatchTimer) -> None:
    """Follow the match ``timer``: once it has ended, board calls end the program."""
    from j5aio.competition.timer import add_game_over_hook

    _timers.append(timer)
    add_game_over_hook(end_of_match)


def end_of_match() -> None:
    """The match is over: log sbot's line (once); later board calls end the program."""
    with _ending:
        if _game_over.is_set():
            return
        _game_over.set()
    _TIMEOUT_LOGGER.info("Timeout expired: Game Over!")


def _match_over() -> bool:
    """Whether the match has ended (the boards are being, or have been, made safe)."""
    return _game_over.is_set() or any(timer.ended_at is not None for timer in _timers)


def _translated(method: Callable[..., Any]) -> Callable[..., Any]:
    @functools.wraps(method)
    def call(*args: Any, **kwargs: Any) -> Any:
        try:
            return method(*args, **kwargs)
        except Exception as error:
            if _match_over():  # the boards are safe and closed: whatever failed, stop
                end_of_match()
                raise SystemExit(0) from None
            if isinstance(error, CommunicationError) and not isinstance(
                error, BoardDisconnectionError,
            ):
                raise BoardDisconnectionError(str(error)) from error
            raise

    return call


def translate_errors(cls: C) -> C:
    """Wrap every public method of ``cls`` (a class of sbot's modules) as described above."""
    for name, value in list(vars(cls).items()):
        if not name.startswith("_") and callable(value):
            setattr(cls, name, _translated(value))
    return cls
