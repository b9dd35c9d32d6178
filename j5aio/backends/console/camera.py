"""The console camera: ``see()`` asks the user which markers the robot would see.

Answer with one marker per comma-separated item, each ``id distance_mm bearing_deg``
(bearing positive to the right), optionally followed by ``elevation_deg`` (positive
upwards); an empty answer
means no marker::

    Camera(SERIAL): Markers seen (id distance_mm bearing_deg, ...): 3 1500 10, 7 2200 -4
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.boards.camera import CameraBoard
from j5aio.components.marker_camera import MarkerCameraInterface
from j5aio.errors import NotSupportedByHardwareError
from j5aio.vision.geometry import position_from_translation
from j5aio.vision.markers import Marker, Orientation, PixelCoordinates
from j5aio.vision.sizes import FAMILY_SIZE

if TYPE_CHECKING:
    from j5aio.boards.board import Board
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image
    from j5aio.vision.sizes import MarkerSizes

__all__ = ["CameraConsoleBackend", "parse_markers"]

_NAN_PIXEL = PixelCoordinates(math.nan, math.nan)


def parse_markers(answer: str) -> list[tuple[int, float, float, float]]:
    """Parse ``"id distance bearing [elevation], ..."`` into (id, mm, rad, rad) tuples.

    :raises ValueError: an item is not 3 or 4 numbers, an id is not a marker id, or a
        distance is not more than 0.
    """
    seen: list[tuple[int, float, float, float]] = []
    for item in answer.split(","):
        words = item.split()
        if not words:
            continue
        if len(words) not in (3, 4):
            raise ValueError(
                f"{item.strip()!r}: give 'id distance_mm bearing_deg' or "
                "'id distance_mm bearing_deg elevation_deg'"
            )
        marker_id = int(words[0])
        if not 0 <= marker_id < FAMILY_SIZE:
            raise ValueError(f"{marker_id} is not an AprilTag 36h11 id (0 to {FAMILY_SIZE - 1})")
        distance = float(words[1])
        if not (math.isfinite(distance) and distance > 0):
            raise ValueError(f"distance {words[1]} must be more than 0 mm")
        bearing = math.radians(float(words[2]))
        elevation = math.radians(float(words[3])) if len(words) == 4 else 0.0
        seen.append((marker_id, distance, bearing, elevation))
    return seen


def _parse_ids(answer: str) -> list[int]:
    ids = sorted(int(word) for word in answer.replace(",", " ").split())
    for marker_id in ids:
        if not 0 <= marker_id < FAMILY_SIZE:
            raise ValueError(f"{marker_id} is not an AprilTag 36h11 id")
    return ids


class CameraConsoleBackend(ConsoleBackend, MarkerCameraInterface):
    """A camera on the console: it asks which markers are in view, and takes no pictures."""

    board: ClassVar[type[Board]] = CameraBoard

    async def see_markers(self, identifier: int, marker_sizes: MarkerSizes) -> list[Marker]:
        """Ask which markers are seen, and where; nearest first."""
        answer = await self._console.read(
            "Markers seen (id distance_mm bearing_deg, ...)", parse_markers
        )
        markers = []
        for marker_id, distance, bearing, elevation in answer:
            size = marker_sizes.size_of(marker_id)
            # The angles are those of the conventions: atan2(right, forward) and
            # atan2(up, forward).
            right, up = math.tan(bearing), math.tan(elevation)
            scale = distance / math.sqrt(1 + right * right + up * up)
            position, cartesian = position_from_translation(
                (right * scale, -up * scale, scale)
            )
            markers.append(
                Marker(
                    marker_id,
                    size,
                    _NAN_PIXEL,
                    (_NAN_PIXEL, _NAN_PIXEL, _NAN_PIXEL, _NAN_PIXEL),
                    position,
                    cartesian,
                    Orientation(0.0, 0.0, 0.0),
                )
            )
        return sorted(markers, key=lambda m: (m.position.distance, m.id))

    async def see_marker_ids(self, identifier: int) -> list[int]:
        """Ask which marker ids are seen."""
        return await self._console.read("Marker ids seen (separated by spaces)", _parse_ids)

    async def capture_frame(self, identifier: int) -> Image:
        """Refuse: the console has no pictures.

        :raises NotSupportedByHardwareError: always.
        """
        raise NotSupportedByHardwareError(
            "the console camera takes no pictures; use the simulated kit or a real camera"
        )

    async def save_annotated_frame(
        self, identifier: int, path: Path, marker_sizes: MarkerSizes
    ) -> None:
        """Refuse: the console has no pictures.

        :raises NotSupportedByHardwareError: always.
        """
        await self.capture_frame(identifier)

    async def get_calibration(self, identifier: int) -> CameraCalibration | None:
        """Return ``None``: the console camera has no lens."""
        return None
