"""Marker sizes: the table, set by the robot or the competition, of each id's size in mm.

The table is made in :mod:`j5aio.components` (the marker camera component holds one, and
vision reads it); this is where its names are documented and imported from.
"""

from __future__ import annotations

from j5aio.components import _marker_sizes
from j5aio.components._marker_sizes import MarkerSizes, UnknownMarkerError

__all__ = ["MarkerSizes", "UnknownMarkerError"]

#: The number of markers in the AprilTag 36h11 family (ids 0 to 586).
FAMILY_SIZE = _marker_sizes.FAMILY_SIZE
