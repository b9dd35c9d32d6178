"""sr-robot3's markers: id, size, pixels, position (mm, radians) and orientation (radians)."""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

from j5aio.vision import markers as core

if TYPE_CHECKING:
    from j5aio.vision.markers import Marker as CoreMarker

__all__ = ["Coordinates", "Marker", "Orientation", "PixelCoordinates", "Position"]


class PixelCoordinates(core.PixelCoordinates):
    """A point on the picture, in pixels (x right, y down from the top left)."""

    __slots__ = ()


class Coordinates(core.Cartesian):
    """A point in space: x forwards, y left, z up."""

    __slots__ = ()


class Orientation(core.Orientation):
    """Which way a marker faces, radians: all 0 when it faces the camera square on."""

    __slots__ = ()


class Position(core.Position):
    """Where a marker is: distance (mm) and the horizontal and vertical angles (radians)."""

    __slots__ = ()


PixelCorners = tuple[PixelCoordinates, PixelCoordinates, PixelCoordinates, PixelCoordinates]


class Marker(NamedTuple):
    """A marker the camera saw.

    :param id: the marker's number.
    :param size: its size in mm.
    :param pixel_corners: its corners on the picture.
    :param pixel_centre: its centre on the picture.
    :param position: where it is from the camera.
    :param orientation: which way it faces.
    """

    id: int
    size: int
    pixel_corners: PixelCorners
    pixel_centre: PixelCoordinates
    position: Position = Position(0, 0, 0)
    orientation: Orientation = Orientation(0, 0, 0)

    @classmethod
    def from_j5aio_marker(cls, marker: CoreMarker) -> Marker:
        """The marker as sr-robot3 gives it: size and distance in whole millimetres.

        :raises ValueError: the marker has no pose (the camera has no calibration).
        """
        if not marker.has_pose:
            raise ValueError("Marker lacks pose information")
        corners = tuple(PixelCoordinates(corner.x, corner.y) for corner in marker.pixel_corners)
        return cls(
            id=marker.id,
            size=round(marker.size),
            pixel_corners=(corners[0], corners[1], corners[2], corners[3]),
            pixel_centre=PixelCoordinates(marker.pixel_centre.x, marker.pixel_centre.y),
            position=Position(
                int(marker.position.distance),
                marker.position.horizontal_angle,
                marker.position.vertical_angle,
            ),
            orientation=Orientation(*marker.orientation),
        )

    def __repr__(self) -> str:
        return (
            f"<{type(self).__name__} id={self.id} distance={self.position.distance:.0f}mm "
            f"horizontal_angle={self.position.horizontal_angle:.2f}rad "
            f"vertical_angle={self.position.vertical_angle:.2f}rad size={self.size}mm>"
        )
