"""What the simulated camera sees: the arena laid out in the camera's frame, and drawn.

Its names are documented, and imported, as :mod:`j5aio.simulator.camera`'s; the camera's
backend (:mod:`j5aio.simulator._camera_backend`) imports it for a first picture.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable

    from j5aio.vision.geometry import Matrix3, Vector3
    from j5aio.vision.image import Image
    from j5aio.vision.render import MarkerItem, QuadItem

    from ._camera_model import SimulatedCamera
    from .arena import ArenaMarker, SimulatedWorld

# The geometry and the renderer are imported by the functions that draw or measure a
# view: finding the camera (every robot on the simulated kit does) needs neither.

__all__ = ["render_view", "scene"]

_FLOOR = (90, 110, 120)
_WALL = (225, 225, 215)
_TOKEN = (60, 160, 230)


def _basis(world: SimulatedWorld) -> tuple[Vector3, Vector3, Vector3, Vector3]:
    h = world.camera_heading()
    forward = (math.cos(h), math.sin(h), 0.0)
    left = (-math.sin(h), math.cos(h), 0.0)
    return world.camera_position(), forward, left, (0.0, 0.0, 1.0)


def _to_camera(world: SimulatedWorld) -> Callable[[Vector3, bool], Vector3]:
    origin, forward, left, up = _basis(world)

    def convert(p: Vector3, is_point: bool = True) -> Vector3:
        d = (p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]) if is_point else p
        return (
            -(d[0] * left[0] + d[1] * left[1] + d[2] * left[2]),
            -(d[0] * up[0] + d[1] * up[1] + d[2] * up[2]),
            d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2],
        )

    return convert


def _marker_item(marker: ArenaMarker, convert: Callable[[Vector3, bool], Vector3]) -> MarkerItem:
    from j5aio.vision.render import MarkerItem

    nx, ny = math.cos(marker.facing), math.sin(marker.facing)
    axes = (convert((-ny, nx, 0.0), False), convert((0.0, 0.0, -1.0), False),
            convert((-nx, -ny, 0.0), False))
    rotation: Matrix3 = (
        (axes[0][0], axes[1][0], axes[2][0]),
        (axes[0][1], axes[1][1], axes[2][1]),
        (axes[0][2], axes[1][2], axes[2][2]),
    )
    # A hair in front of its surface, so that the surface never covers it.
    centre = convert((marker.x + nx * 0.5, marker.y + ny * 0.5, marker.z), True)
    return MarkerItem(marker.marker_id, marker.size, centre, rotation)


def _depth(points: Sequence[Vector3]) -> float:
    return sum(p[2] for p in points) / len(points)


def scene(world: SimulatedWorld) -> list[QuadItem | MarkerItem]:
    """Everything the camera could see, in camera coordinates, far things first."""
    from j5aio.vision.render import QuadItem

    convert = _to_camera(world)
    arena = world.arena
    w, length, h = arena.width, arena.length, arena.wall_height
    corners = [(0.0, 0.0), (w, 0.0), (w, length), (0.0, length)]
    items: list[QuadItem | MarkerItem] = [
        QuadItem(tuple(convert((x, y, 0.0), True) for x, y in corners), _FLOOR)  # type: ignore[arg-type]
    ]
    walls: list[QuadItem] = []
    for i in range(4):
        (x0, y0), (x1, y1) = corners[i], corners[(i + 1) % 4]
        quad = tuple(
            convert(p, True) for p in ((x0, y0, 0.0), (x1, y1, 0.0), (x1, y1, h), (x0, y0, h))
        )
        walls.append(QuadItem(quad, _WALL))  # type: ignore[arg-type]
    walls.sort(key=lambda wall: -_depth(wall.corners))
    items += walls
    items += [_marker_item(m, convert) for m in arena.markers]
    tokens = []
    for token in arena.tokens:
        half = token.side / 2
        faces: list[QuadItem | MarkerItem] = []
        for k in range(4):
            a = token.heading + k * math.pi / 2
            nx, ny = math.cos(a), math.sin(a)
            tx, ty = -ny, nx
            cx, cy = token.x + nx * half, token.y + ny * half
            quad = tuple(
                convert((cx + sx * tx * half, cy + sx * ty * half, z), True)
                for sx, z in ((-1, 0.0), (1, 0.0), (1, token.side), (-1, token.side))
            )
            centre = convert((cx, cy, half), True)
            normal = convert((nx, ny, 0.0), False)
            if centre[0] * normal[0] + centre[1] * normal[1] + centre[2] * normal[2] < 0:
                faces.append(QuadItem(quad, _TOKEN))  # type: ignore[arg-type]
        faces += [_marker_item(m, convert) for m in token.markers()]
        centre = convert((token.x, token.y, half), True)
        tokens.append((centre[2], faces))
    for _, faces in sorted(tokens, key=lambda t: -t[0]):
        items += faces
    return items


def render_view(world: SimulatedWorld, camera: SimulatedCamera) -> Image:
    """Render what the camera sees from the robot's pose now (needs the vision extra)."""
    from j5aio.vision.render import render

    calibration, resolution = camera.model()
    return render(calibration, resolution, scene(world), lighting=camera.lighting)



# Documented, and imported, as j5aio.simulator.camera's.
scene.__module__ = render_view.__module__ = "j5aio.simulator.camera"
