"""Marker sizes: the table, set by the robot or the competition, of each id's size in mm.

The marker camera component holds one (:mod:`j5aio.components.marker_camera`) and vision
reads it, so it lives here, below both. Its names are documented, and imported, as
:mod:`j5aio.vision.sizes`'s.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator, Mapping

from j5aio.components._checks import check_number

__all__ = ["FAMILY_SIZE", "MarkerSizes", "UnknownMarkerError"]

#: The number of markers in the AprilTag 36h11 family (documented as
#: :data:`j5aio.vision.sizes.FAMILY_SIZE`).
FAMILY_SIZE = 587


class UnknownMarkerError(LookupError):
    """A marker was seen whose id has no size in the game's table."""

    __module__ = "j5aio.vision.sizes"  # where it is documented, and imported from


def _check_size(marker_id: int, size: object) -> float:
    return check_number(
        size,
        name=f"the size of marker {marker_id}",
        low=sys.float_info.min,
        high=sys.float_info.max,
        allowed="a number of mm more than 0",
    )


def _check_id(marker_id: object) -> int:
    if isinstance(marker_id, bool) or not isinstance(marker_id, int):
        raise TypeError(f"a marker id must be an int, not {marker_id!r}")
    if not 0 <= marker_id < FAMILY_SIZE:
        raise ValueError(
            f"marker id {marker_id} is not in AprilTag 36h11 (ids 0 to {FAMILY_SIZE - 1})"
        )
    return marker_id


class MarkerSizes(Mapping[int, float]):
    """Which size (mm, the edge of the black square) each marker id has in a game.

    ::

        sizes = MarkerSizes({0: 150, 1: 150}) | MarkerSizes.of_range(range(100, 120), 80)

    :param sizes: id to size in mm.
    :param default: the size of every id not in ``sizes``; ``None`` (the default) means
        that such an id is an error.
    :raises TypeError: an id is not an int or a size not a number.
    :raises ValueError: an id is outside 0-586 or a size is not more than 0.
    """

    __module__ = "j5aio.vision.sizes"  # where it is documented, and imported from

    def __init__(self, sizes: Mapping[int, float] | None = None, *, default: float | None = None):
        self._sizes = {_check_id(k): _check_size(k, v) for k, v in (sizes or {}).items()}
        self._default = None if default is None else _check_size(-1, default)

    @classmethod
    def of_range(cls, ids: Iterable[int], size: float) -> MarkerSizes:
        """Return a table giving every id in ``ids`` the same ``size``."""
        return cls(dict.fromkeys(ids, size))

    @property
    def default(self) -> float | None:
        """The size of ids not in the table, or ``None`` when they are an error."""
        return self._default

    def size_of(self, marker_id: int) -> float:
        """Return the size of ``marker_id`` in mm.

        :raises UnknownMarkerError: the id has no size and there is no default.
        """
        size = self._sizes.get(marker_id, self._default)
        if size is None:
            known = _describe(sorted(self._sizes))
            raise UnknownMarkerError(
                f"marker {marker_id} was seen, but the game's table of marker sizes has no "
                f"size for it (it has sizes for {known}). Add it, e.g. "
                f"camera.marker_sizes = camera.marker_sizes | MarkerSizes({{{marker_id}: 150}}), "
                "or give the table a default size.",
            )
        return size

    def __getitem__(self, marker_id: int) -> float:
        return self._sizes[marker_id]

    def __iter__(self) -> Iterator[int]:
        return iter(self._sizes)

    def __len__(self) -> int:
        return len(self._sizes)

    def __or__(self, other: Mapping[int, float]) -> MarkerSizes:
        default = other.default if isinstance(other, MarkerSizes) else None
        merged = MarkerSizes({**self._sizes, **dict(other)})
        merged._default = default if default is not None else self._default
        return merged

    def __repr__(self) -> str:
        return f"MarkerSizes({self._sizes!r}, default={self._default!r})"


def _describe(ids: list[int]) -> str:
    if not ids:
        return "no id"
    runs: list[str] = []
    start = prev = ids[0]
    for i in [*ids[1:], None]:
        if i is not None and i == prev + 1:
            prev = i
            continue
        runs.append(str(start) if start == prev else f"{start}-{prev}")
        if i is not None:
            start = prev = i
    return "ids " + ", ".join(runs)
