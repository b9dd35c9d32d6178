"""Markers as a perfect camera would report them, from the simulated world's geometry.

For the maths of locating (no picture, no optional library): each marker the camera has
in view, with its true position and orientation, and pixel corners of its true size.
"""

from __future__ import annotations

import math

from j5aio.simulator.arena import SimulatedWorld
from j5aio.simulator.camera import DEFAULT_CALIBRATION, SimulatedCamera, visible_markers
from j5aio.vision.geometry import (
    matmul,
    orientation_from_rotation,
    position_from_translation,
    rotation_from_orientation,
)
from j5aio.vision.markers import Marker, PixelCoordinates, Position

__all__ = ["true_markers"]


def _translation(position: Position) -> tuple[float, float, float]:
    """OpenCV's (right, down, forward) of a point at ``position``."""
    distance, horizontal, vertical = position
    forward = distance / math.sqrt(1 + math.tan(horizontal) ** 2 + math.tan(vertical) ** 2)
    return (forward * math.tan(horizontal), -forward * math.tan(vertical), forward)


def true_markers(
    world: SimulatedWorld,
    *,
    tilt: float = 0.0,
    sizes: dict[int, float] | None = None,
    pixels: float | None = None,
) -> list[Marker]:
    """What the camera sees from ``world``'s pose, exactly, nearest first.

    :param tilt: report as if the camera looked up by this much (radians) from level.
    :param sizes: sizes the camera takes some ids to be (distances scale with them).
    :param pixels: the width in pixels each marker is given (by default its true width).
    """
    # The tilted camera's axes (right, down, forward) in the level camera's frame.
    axes = (
        (1.0, 0.0, 0.0),
        (0.0, math.cos(tilt), math.sin(tilt)),
        (0.0, -math.sin(tilt), math.cos(tilt)),
    )
    found = []
    for seen in visible_markers(world, SimulatedCamera()):
        size = next(m.size for m in world.arena.all_markers() if m.marker_id == seen.marker_id)
        reported = (sizes or {}).get(seen.marker_id, size)
        level = _translation(seen.position)
        t = tuple(sum(axes[i][k] * level[k] for k in range(3)) * reported / size for i in range(3))
        rotation = matmul(axes, rotation_from_orientation(seen.orientation))
        position, cartesian = position_from_translation(t)
        true_width = DEFAULT_CALIBRATION.fx * size / seen.position.distance
        width = pixels if pixels is not None else true_width
        cx = DEFAULT_CALIBRATION.fx * t[0] / t[2] + DEFAULT_CALIBRATION.cx
        cy = DEFAULT_CALIBRATION.fy * t[1] / t[2] + DEFAULT_CALIBRATION.cy
        h = width / 2
        corners = (
            PixelCoordinates(cx - h, cy + h),
            PixelCoordinates(cx + h, cy + h),
            PixelCoordinates(cx + h, cy - h),
            PixelCoordinates(cx - h, cy - h),
        )
        found.append(
            Marker(
                seen.marker_id, reported, PixelCoordinates(cx, cy), corners, position, cartesian,
                orientation_from_rotation(rotation),
            )
        )
    return found
