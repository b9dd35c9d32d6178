"""The game's marker sizes, as sr-robot3 2026.0.3 gives them (ids to mm)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Final

__all__ = ["MARKER_SIZES", "marker_size_table"]

#: Marker ids to their size in mm.
MARKER_SIZES: Final[dict[Iterable[int], int]] = {
    range(50): 150,
    range(50, 100): 200,
    range(100, 200): 80,
}


def marker_size_table() -> dict[int, float]:
    """:data:`MARKER_SIZES` with one entry per id."""
    return {marker: float(size) for ids, size in MARKER_SIZES.items() for marker in ids}
