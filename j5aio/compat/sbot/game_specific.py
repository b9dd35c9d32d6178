"""The game's facts that sbot's API uses: the match's length and the markers' sizes."""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["GAME_LENGTH", "MARKER_SIZES"]

#: The length of a match, in seconds.
GAME_LENGTH = 150

#: The markers' sizes in mm: the arena's boundary markers, then the tokens.
MARKER_SIZES: dict[Iterable[int], int] = {
    range(28): 100,
    range(28, 100): 80,
}
