"""Every board made safe, however the program ends: the guarantee, in one place.

- :mod:`~j5aio.safety.registry`: the one registry of boards and their states (open, set
  up, settled), and game over's seal: after game over no board can be opened;
- :mod:`~j5aio.safety.orderly`: the orderly async path
  (:func:`~j5aio.safety.orderly.make_all_safe_uncancellably`, which cancellation cannot
  interrupt), used by a robot and the sync facade on the way out;
- :mod:`~j5aio.safety.rescue`: the sync rescue
  (:func:`~j5aio.safety.rescue.make_all_safe_now`), which makes every board still open
  safe through its own link from any thread, within a budget;
- :mod:`~j5aio.safety.hooks`: when the rescue runs (the end of an event loop, the end of
  the interpreter, SIGTERM / SIGHUP, an unhandled exception), installed by the entry
  points, not by making a board.

In a match, game over (:mod:`j5aio.competition.timer`) uses the rescue, and the match
supervisor (:mod:`j5aio.competition.supervisor`) makes the boards safe from outside the
program's interpreter when the program holds game over back.
"""

from __future__ import annotations

from j5aio.safety.hooks import add_exit_step, install, on_terminate, quiet_interrupts
from j5aio.safety.orderly import SAFE_STATE_TIMEOUT, make_all_safe, make_all_safe_uncancellably
from j5aio.safety.registry import (
    begin_game_over,
    game_over_begun,
    mark_settled,
    open_boards,
    track,
    untrack,
    wait_for_game_over,
)
from j5aio.safety.rescue import NET_BUDGET, PER_BOARD_TIMEOUT, make_all_safe_now

__all__ = [
    "NET_BUDGET",
    "PER_BOARD_TIMEOUT",
    "SAFE_STATE_TIMEOUT",
    "add_exit_step",
    "begin_game_over",
    "game_over_begun",
    "install",
    "make_all_safe",
    "make_all_safe_now",
    "make_all_safe_uncancellably",
    "mark_settled",
    "on_terminate",
    "open_boards",
    "quiet_interrupts",
    "track",
    "untrack",
    "wait_for_game_over",
]
