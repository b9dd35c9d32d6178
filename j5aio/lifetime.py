"""The safety net's former home; everything is in :mod:`j5aio.safety` now.

Kept so that code written against it keeps working: each name here is the one of
:mod:`j5aio.safety`'s modules (the registry, the rescue and the process hooks).
"""

from __future__ import annotations

from j5aio.safety.hooks import add_exit_step, install, on_terminate, quiet_interrupts
from j5aio.safety.registry import (
    GAME_OVER_WAIT,
    begin_game_over,
    end_game_over,
    game_over_begun,
    mark_settled,
    open_boards,
    track,
    untrack,
    wait_for_game_over,
)
from j5aio.safety.rescue import NET_BUDGET, PER_BOARD_TIMEOUT, make_all_safe_now

__all__ = [
    "GAME_OVER_WAIT",
    "NET_BUDGET",
    "PER_BOARD_TIMEOUT",
    "add_exit_step",
    "begin_game_over",
    "end_game_over",
    "game_over_begun",
    "install",
    "make_all_safe_now",
    "mark_settled",
    "on_terminate",
    "open_boards",
    "quiet_interrupts",
    "track",
    "untrack",
    "wait_for_game_over",
]
