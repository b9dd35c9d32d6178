"""What a camera reports about each marker it sees, with sr-robot3 / sbot names and units.

Axes and signs (see the vision tutorial for pictures):

* ``position``: ``distance`` in mm from the camera to the marker's centre;
  ``horizontal_angle`` positive to the right, ``vertical_angle`` positive upwards, radians.
* ``cartesian``: the camera's frame as the student sees it: ``x`` forwards, ``y`` to the
  left, ``z`` upwards, mm.
* ``orientation``: ``yaw`` (about the vertical axis), ``pitch`` (about the horizontal axis
  across the view) and ``roll`` (about the line of sight), radians, composed as
  ``R = Rx(roll) · Ry(pitch) · Rz(yaw)``; all three are about 0 for a marker that faces
  the camera squarely, the right way up.
* ``pixel_centre``: where the marker's centre projects (the homography centre, not the
  mean of the corners); ``pixel_corners`` in the detector's order (anticlockwise on the
  picture, starting at the marker's bottom left).
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = ["Cartesian", "Marker", "Orientation", "PixelCoordinates", "Position"]


class PixelCoordinates(NamedTuple):
    """A point on the picture, in pixels from its top-left corner (x right, y down)."""

    x: float
    y: float


class Position(NamedTuple):
    """Where a marker is, as a distance and two angles from the camera."""

    distance: float
    """Straight-line distance from the camera to the marker's centre, mm."""
    horizontal_angle: float
    """Angle to the right of straight ahead, radians."""
    vertical_angle: float
    """Angle above straight ahead, radians."""


class Cartesian(NamedTuple):
    """Where a marker is, in mm in the camera's frame: x forwards, y left, z up."""

    x: float
    y: float
    z: float


class Orientation(NamedTuple):
    """Which way a marker faces, radians; all about 0 when it faces the camera squarely."""

    yaw: float
    """Turn about the vertical axis."""
    pitch: float
    """Tilt about the horizontal axis across the view."""
    roll: float
    """Turn about the line of sight."""


_NAN3 = (math.nan, math.nan, math.nan)


class Marker(NamedTuple):
    """One marker in a picture.

    Without a camera calibration, ``position``, ``cartesian`` and ``orientation`` hold NaN
    (``has_pose`` is ``False``): the id and the pixels are still known.
    """

    id: int
    """The marker's number in the AprilTag 36h11 family."""
    size: float
    """The edge of its black square, mm, from the game's table of sizes."""
    pixel_centre: PixelCoordinates
    """Where its centre is on the picture."""
    pixel_corners: tuple[PixelCoordinates, PixelCoordinates, PixelCoordinates, PixelCoordinates]
    """Its four corners on the picture."""
    position: Position = Position(*_NAN3)
    """Distance and angles from the camera (NaN without a calibration)."""
    cartesian: Cartesian = Cartesian(*_NAN3)
    """x forwards, y left, z up from the camera, mm (NaN without a calibration)."""
    orientation: Orientation = Orientation(*_NAN3)
    """Which way it faces (NaN without a calibration)."""

    @property
    def has_pose(self) -> bool:
        """Whether distances and angles are known (the camera has a calibration)."""
        return not math.isnan(self.position.distance)

    @property
    def distance(self) -> float:
        """Shorthand for ``position.distance``, mm."""
        return self.position.distance

    def __str__(self) -> str:
        if not self.has_pose:
            centre = self.pixel_centre
            return f"<Marker {self.id}: at pixel ({centre.x:.0f}, {centre.y:.0f}), no pose>"
        return (
            f"<Marker {self.id}: {self.position.distance:.0f} mm away, "
            f"{math.degrees(self.position.horizontal_angle):.1f}° right, "
            f"{math.degrees(self.position.vertical_angle):.1f}° up>"
        )
