"""The simulated camera: renders what the robot's camera sees in the simulated arena.

The picture is drawn by :func:`j5aio.vision.render.render` from the robot's pose in the
kit's :class:`~j5aio.simulator.arena.SimulatedWorld`, then handed to the same detector as a
real camera's, so ``see()`` in simulation runs the whole real pipeline.

While a simulated camera exists, the world is moved on every 10 ms (a timer on the event
loop) and before each picture, from the powers of the kit's motors: see the drive model in
:mod:`j5aio.simulator.arena`.
"""

from __future__ import annotations

import asyncio
import copy
import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.boards.camera import CameraBoard

from . import _camera_model
from ._camera_model import SimulatedCamera
from .arena import ArenaMarker, SimulatedWorld
from .kit import SimulatedKit, current_kit

if TYPE_CHECKING:
    from collections.abc import Callable

    from j5aio.backends.hardware.options import DiscoveryOptions
    from j5aio.boards.board import Board
    from j5aio.vision.geometry import Matrix3, Vector3
    from j5aio.vision.image import Image
    from j5aio.vision.markers import Orientation, Position
    from j5aio.vision.render import MarkerItem, QuadItem

# The geometry and the renderer are imported by the functions that draw or measure a
# view: finding the camera (every robot on the simulated kit does) needs neither.

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

#: How often the world is moved on while a simulated camera exists, seconds.
TICK = 0.01

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


def render_view(world: SimulatedWorld, camera: SimulatedCamera) -> Image:
    """Render what the camera sees from the robot's pose now (needs the vision extra)."""
    from j5aio.vision.render import render

    calibration, resolution = camera.model()
    return render(calibration, resolution, scene(world), lighting=camera.lighting)


class SimulatedCameraBackend(FrameCameraBackend):
    """The camera of the simulated kit: pictures rendered from the robot's pose.

    :param kit: the kit whose world (arena, pose, motors) the camera looks at.
    """

    board: ClassVar[type[Board]] = CameraBoard

    def __init__(self, kit: SimulatedKit) -> None:
        world_camera = kit.camera
        if world_camera is None:
            raise ValueError(f"{kit.name} has no camera")
        calibration, _ = world_camera.model()
        super().__init__(f"SIMCAM-{kit.name}", calibration)
        self._kit = kit
        self._camera = world_camera
        #: The table of the arena's marker sizes, which the camera starts with.
        self.marker_sizes = kit.world.arena.marker_sizes()
        self._ticking = False

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current kit's camera (none if its world has no camera).

        ``options`` (for serial and USB discovery) is accepted and ignored.
        """
        kit = current_kit()
        if kit.camera is None:
            return []
        backend = cls(kit)
        backend._start_ticking()
        return [CameraBoard(backend.name, backend)]

    @property
    def kit(self) -> SimulatedKit:
        """The kit the camera belongs to."""
        return self._kit

    def _start_ticking(self) -> None:
        _WorldClock.join(self._kit, asyncio.get_running_loop())
        self._ticking = True

    def grab(self) -> Image:
        """Render the view from the pose the robot has now (call on the event loop)."""
        return render_view(self._kit.world, self._camera)

    async def frame_source(self) -> Callable[[], Image]:
        """Move the world to now, note it, and return the call that renders its view.

        Only a shallow copy of the world (a few microseconds) is made here, on the event
        loop; the scene is laid out and drawn by the returned call, on the worker thread.
        The copy holds the robot's pose of this moment: the arena, its markers and tokens
        are immutable, so the worker never reads what the loop changes.
        """
        update_world(self._kit)
        return functools.partial(render_view, copy.copy(self._kit.world), self._camera)

    async def close(self) -> None:
        """Stop moving the world on, and stop the worker thread."""
        if self._ticking:
            self._ticking = False
            _WorldClock.leave(self._kit)
        await super().close()


class _WorldClock:
    """Moves a kit's world on while any of its cameras is open.

    One clock a kit, on the event loop of the camera that started it, however many camera
    backends have been made for the kit. While the robot drives it ticks every
    :data:`TICK` (so that the walls stop it where they are); while every drive motor is
    still it sleeps, and a motor board's next command wakes it: an idle robot costs
    nothing, and the world is moved on at the very moment the powers change.
    """

    _clocks: ClassVar[dict[int, _WorldClock]] = {}

    def __init__(self, kit: SimulatedKit, loop: asyncio.AbstractEventLoop) -> None:
        self.kit = kit
        self.loop = loop
        self.users = 0
        self.timer: asyncio.TimerHandle | None = None
        self._stop_listening = [board.listen(self._changed) for board in kit.drive_motor_boards]

    @classmethod
    def join(cls, kit: SimulatedKit, loop: asyncio.AbstractEventLoop) -> None:
        clock = cls._clocks.get(id(kit))
        if clock is None or clock.kit is not kit or clock.loop is not loop or loop.is_closed():
            if clock is not None:
                clock.stop()
            clock = cls._clocks[id(kit)] = cls(kit, loop)
            clock.tick()
        clock.users += 1

    @classmethod
    def leave(cls, kit: SimulatedKit) -> None:
        clock = cls._clocks.get(id(kit))
        if clock is None or clock.kit is not kit:
            return
        clock.users -= 1
        if clock.users <= 0:
            clock.stop()
            del cls._clocks[id(kit)]

    def stop(self) -> None:
        """Stop ticking and listening to the motor boards."""
        if self.timer is not None:
            self.timer.cancel()
            self.timer = None
        for stop in self._stop_listening:
            stop()
        self._stop_listening = []

    def tick(self) -> None:
        """Move the world on now; tick again soon while the robot drives."""
        self.timer = None
        if not update_world(self.kit) or self.loop.is_closed():
            return
        self.timer = self.loop.call_later(TICK, self.tick)

    def _changed(self) -> None:
        # A motor board took a command (in whatever thread fed it): move the world on to
        # now with the powers held until now, and tick if the robot now drives.
        if self.loop.is_closed():
            return
        try:
            running = asyncio.get_running_loop()
        except RuntimeError:
            running = None
        if running is self.loop:
            self._wake()
        else:
            self.loop.call_soon_threadsafe(self._wake)

    def _wake(self) -> None:
        if self.timer is not None:
            update_world(self.kit)  # ticking already: only take the new powers now
            return
        self.tick()


def update_world(kit: SimulatedKit, now: float | None = None) -> bool:
    """Move ``kit``'s robot on to ``now`` from its motors.

    ``now`` is a time of the kit's clock (``kit.clock``, :mod:`j5aio.simulator.clock`),
    its present by default: the robot drives in the kit's time, as its boards' timers
    run, so under a time scale of 2 a robot second of driving lasts two real seconds.

    :returns: whether the robot drives on from ``now`` (a drive motor's power is not 0).
    """
    drive = kit.world.drive
    powers = []
    for board_index, motor_index in (drive.left, drive.right):
        try:
            powers.append(kit.drive_motor_boards[board_index].motors[motor_index].power)
        except IndexError:
            powers.append(0.0)
    kit.world.update(kit.clock.now() if now is None else now, powers[0], powers[1])
    return powers[0] != 0 or powers[1] != 0
