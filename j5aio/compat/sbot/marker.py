"""sbot's marker: what the camera reports about each marker it sees, in sbot's units.

``vision.detect_markers()`` returns a list of ``Marker``, each a named tuple of ``id``,
``size`` (mm), ``pixel_corners`` and ``pixel_centre`` (``PixelCoordinates``: ``x``,
``y``), ``position`` (``Position``: ``distance`` in whole mm, ``horizontal_angle``
positive to the right and ``vertical_angle`` positive upwards, in radians) and
``orientation`` (:class:`j5aio.vision.markers.Orientation`: ``yaw``, ``pitch``,
``roll`` in radians). They are made from j5aio's own markers
(:class:`j5aio.vision.markers.Marker`), which use the same axes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

from j5aio.vision import markers as core
from j5aio.vision.markers import Orientation

if TYPE_CHECKING:
    from j5aio.vision.markers import Marker as CoreMarker

__all__ = ["Coordinates", "Marker", "PixelCoordinates", "PixelCorners", "Position"]


class PixelCoordinates(core.PixelCoordinates):
    """A point on the picture, in pixels from its top-left corner (x right, y down)."""

    __slots__ = ()


class Coordinates(core.Cartesian):
    """A point in space, mm: x straight out of the camera, y to its left, z up."""

    __slots__ = ()


class Position(core.Position):
    """Where a marker is from the camera.

    ``distance`` in whole mm; ``horizontal_angle`` in radians, positive to the right;
    ``vertical_angle`` in radians, positive upwards.
    """

    __slots__ = ()


PixelCorners = tuple[PixelCoordinates, PixelCoordinates, PixelCoordinates, PixelCoordinates]
"""A marker's four corners on the picture."""


class Marker(NamedTuple):
    """A marker the camera saw.

    ``size`` in mm; ``pixel_corners`` and ``pixel_centre`` on the picture;
    ``position`` from the camera; ``orientation`` (a
    :class:`~j5aio.vision.markers.Orientation`: yaw, pitch, roll in radians) of the marker.
    """

    id: int
    size: int
    pixel_corners: PixelCorners
    pixel_centre: PixelCoordinates
    position: Position = Position(0, 0, 0)
    orientation: Orientation = Orientation(0, 0, 0)

    @classmethod
    def from_core(cls, marker: CoreMarker) -> Marker:
        """The sbot marker for a marker j5aio's camera saw (sizes and distances in mm).

        :raises ValueError: the marker has no pose (the camera has no calibration).
        """
        if not marker.has_pose:
            raise ValueError("Marker lacks pose information")
        return cls(
            id=marker.id,
            size=int(marker.size),
            pixel_corners=(
                PixelCoordinates(*marker.pixel_corners[0]),
                PixelCoordinates(*marker.pixel_corners[1]),
                PixelCoordinates(*marker.pixel_corners[2]),
                PixelCoordinates(*marker.pixel_corners[3]),
            ),
            pixel_centre=PixelCoordinates(*marker.pixel_centre),
            position=Position(
                distance=int(marker.position.distance),
                horizontal_angle=marker.position.horizontal_angle,
                vertical_angle=marker.position.vertical_angle,
            ),
            orientation=marker.orientation,
        )

    def __repr__(self) -> str:
        return (
            f"<{self.__class__.__name__} id={self.id} distance={self.position.distance:.0f}mm "
            f"horizontal_angle={self.position.horizontal_angle:.2f}rad "
            f"vertical_angle={self.position.vertical_angle:.2f}rad size={self.size}mm>"
        )
