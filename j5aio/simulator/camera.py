"""The simulated camera: renders what the robot's camera sees in the simulated arena.

The picture is drawn by :func:`j5aio.vision.render.render` from the robot's pose in the
kit's :class:`~j5aio.simulator.arena.SimulatedWorld`, then handed to the same detector as a
real camera's, so ``see()`` in simulation runs the whole real pipeline.

While a simulated camera exists, the world is moved on every 10 ms (a timer on the event
loop) and before each picture, from the powers of the kit's motors: see the drive model in
:mod:`j5aio.simulator.arena`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from . import _camera_model

# Finding the camera (every robot on the simulated kit does) imports only its backend
# (with its world clock and update_world); this module, the arena, the camera's model,
# the drawing of the view and the vision modules are imported for a first picture.
from ._camera_backend import TICK as TICK
from ._camera_backend import SimulatedCameraBackend, update_world
from ._camera_backend import _WorldClock as _WorldClock
from ._camera_model import SimulatedCamera
from ._camera_view import _marker_item, _to_camera, scene
from ._camera_view import render_view as render_view

if TYPE_CHECKING:
    from j5aio.vision.markers import Orientation, Position

    from .arena import SimulatedWorld

__all__ = [
    "DEFAULT_CALIBRATION",
    "SimulatedCamera",
    "SimulatedCameraBackend",
    "VisibleMarker",
    "scene",
    "update_world",
    "visible_markers",
]

#: The simulated camera's default: an ideal (distortion-free) Logitech C270 at 1280x720,
#: where it crops the middle of its 1280x960 sensor (so the focal length of its
#: 1280x960 calibration, 1387.5 px: a 55° diagonal field of view, as Logitech states).
DEFAULT_CALIBRATION = _camera_model.DEFAULT_CALIBRATION


@dataclass(frozen=True)
class VisibleMarker:
    """Where a marker truly is from the camera: what a perfect ``see()`` would report."""

    marker_id: int
    position: Position
    orientation: Orientation


def visible_markers(world: SimulatedWorld, camera: SimulatedCamera) -> list[VisibleMarker]:
    """The markers wholly in the camera's view and facing it, nearest first (the truth).

    Markers hidden behind tokens are included: the renderer does not hide them either.
    """
    from j5aio.vision.geometry import orientation_from_rotation, position_from_translation
    from j5aio.vision.render import NEAR_PLANE

    calibration, (width, height) = camera.model()
    convert = _to_camera(world)
    found = []
    for marker in world.arena.all_markers():
        item = _marker_item(marker, convert)
        corners = item.corners(1.25)
        if min(c[2] for c in corners) < NEAR_PLANE:
            continue
        if sum(a * b for a, b in zip(item.centre, (r[2] for r in item.rotation), strict=True)) <= 0:
            continue
        inside = all(
            0 <= calibration.fx * x / z + calibration.cx <= width - 1
            and 0 <= calibration.fy * y / z + calibration.cy <= height - 1
            for x, y, z in corners
        )
        if inside:
            position, _ = position_from_translation(item.centre)
            found.append(
                VisibleMarker(marker.marker_id, position, orientation_from_rotation(item.rotation))
            )
    return sorted(found, key=lambda m: m.position.distance)
