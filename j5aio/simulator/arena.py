"""The simulated arena: walls with markers, tokens with markers, and the robot's pose.

Pure geometry, with no numpy: the simulated camera (:mod:`j5aio.simulator.camera`) turns
it into pictures. The world frame has its origin at the arena's south-west corner, x east,
y north, z up, in mm; a heading is measured from east towards north, in radians.

**Drive model.** The robot is a differential drive: a left and a right wheel, each driven
by one motor of the simulated kit (by default motor 0 and motor 1 of motor board 0). A
wheel's ground speed is its motor's signed duty as the simulated board drives it (-1 to 1:
``MotorOutput.power``, which is what the firmware makes of the power sent, e.g. 62 % for
0.5 on an SR v4 motor board) times the ``max_speed`` of
:class:`~j5aio.simulator.arena.DifferentialDrive`. The robot moves forwards at the mean of
the two speeds and turns anticlockwise at their difference divided by the track width; the
pose is integrated exactly along each arc, with each power held from one update to the
next.
The robot stops at the walls (it cannot leave the arena); tokens do not stop it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from j5aio.vision.sizes import MarkerSizes

if TYPE_CHECKING:  # (imported where used: a kit that never locates itself needs neither)
    from j5aio.vision.arena_map import ArenaMap
    from j5aio.vision.locate import CameraMount

__all__ = [
    "Arena",
    "ArenaMarker",
    "DifferentialDrive",
    "Pose",
    "SimulatedWorld",
    "Token",
]


@dataclass(frozen=True)
class ArenaMarker:
    """A marker fixed in the arena.

    :param marker_id: its AprilTag 36h11 id.
    :param size: the edge of its black square, mm.
    :param x: x of its centre, mm.
    :param y: y of its centre, mm.
    :param z: height of its centre, mm.
    :param facing: the heading its face points to (the way a person reading it looks is
        the opposite), radians.
    """

    marker_id: int
    size: float
    x: float
    y: float
    z: float
    facing: float


@dataclass(frozen=True)
class Token:
    """A cube on the floor with the same marker on each of its four sides.

    :param marker_id: the id of its markers.
    :param x: x of its centre, mm.
    :param y: y of its centre, mm.
    :param side: the edge of the cube, mm.
    :param marker_size: the edge of each marker's black square, mm.
    :param heading: which way its first face points, radians.
    """

    marker_id: int
    x: float
    y: float
    side: float = 130.0
    marker_size: float = 80.0
    heading: float = 0.0

    def markers(self) -> list[ArenaMarker]:
        """The four markers on its sides."""
        half = self.side / 2
        out = []
        for k in range(4):
            facing = self.heading + k * math.pi / 2
            out.append(
                ArenaMarker(
                    self.marker_id,
                    self.marker_size,
                    self.x + half * math.cos(facing),
                    self.y + half * math.sin(facing),
                    half,
                    facing,
                )
            )
        return out


@dataclass(frozen=True)
class Arena:
    """A rectangular arena with markers on its walls and tokens on its floor.

    :param width: its size along x, mm.
    :param length: its size along y, mm.
    :param wall_height: mm.
    :param markers: the wall markers.
    :param tokens: the tokens.
    """

    width: float = 5750.0
    length: float = 5750.0
    wall_height: float = 500.0
    markers: tuple[ArenaMarker, ...] = ()
    tokens: tuple[Token, ...] = ()

    @classmethod
    def standard(
        cls,
        *,
        size: float = 5750.0,
        markers_per_wall: int = 7,
        marker_size: float = 150.0,
        marker_height: float = 250.0,
    ) -> Arena:
        """A square arena like SR's: ``markers_per_wall`` markers evenly along each wall.

        Ids go anticlockwise from 0, starting at the west end of the south wall; four
        tokens (ids 100-103, 80 mm markers) stand around the middle. The walls are those
        of :meth:`ArenaMap.standard <j5aio.vision.arena_map.ArenaMap.standard>`, the map a
        robot locates itself by.
        """
        # The simulated arena is made from the map (imported where it is needed).
        from j5aio.vision.arena_map import ArenaMap

        layout = ArenaMap.standard(
            size=size,
            markers_per_wall=markers_per_wall,
            marker_size=marker_size,
            marker_height=marker_height,
        )
        markers = tuple(
            ArenaMarker(m.id, m.size, m.x, m.y, m.z, m.facing) for m in layout.markers
        )
        middle = size / 2
        headings = (math.pi / 4, 3 * math.pi / 4, -3 * math.pi / 4, -math.pi / 4)
        tokens = tuple(
            Token(
                marker_id,
                middle + 700 * math.cos(a),
                middle + 700 * math.sin(a),
                marker_size=marker_size_of_token,
                heading=a,
            )
            for (marker_id, marker_size_of_token), a in zip(
                sorted(layout.token_sizes.items()), headings, strict=True
            )
        )
        return cls(size, size, 500.0, markers, tokens)

    def all_markers(self) -> Iterator[ArenaMarker]:
        """Every marker: the walls', then each token's four."""
        yield from self.markers
        for token in self.tokens:
            yield from token.markers()

    def marker_sizes(self) -> MarkerSizes:
        """The table of sizes of every marker id in the arena."""
        return MarkerSizes({m.marker_id: m.size for m in self.all_markers()})

    def arena_map(self) -> ArenaMap:
        """The map a robot locates itself by: the wall markers and the tokens' ids."""
        from j5aio.vision.arena_map import ArenaMap, WallMarker

        return ArenaMap(
            tuple(WallMarker(m.marker_id, m.x, m.y, m.facing, m.size, m.z) for m in self.markers),
            width=self.width,
            length=self.length,
            token_sizes={t.marker_id: t.marker_size for t in self.tokens},
        )


@dataclass(frozen=True)
class Pose:
    """Where the robot is: x, y (mm) of its centre and its heading (radians, from east)."""

    x: float
    y: float
    heading: float


@dataclass(frozen=True)
class DifferentialDrive:
    """Which motors drive the wheels, and how fast the robot goes.

    :param left: (motor board index, motor index) of the left wheel.
    :param right: (motor board index, motor index) of the right wheel.
    :param max_speed: ground speed of a wheel at full power, mm/s.
    :param track_width: distance between the wheels, mm.
    :param radius: how far the robot reaches from its centre, mm (it stops at the walls).
    """

    left: tuple[int, int] = (0, 0)
    right: tuple[int, int] = (0, 1)
    max_speed: float = 1000.0
    track_width: float = 300.0
    radius: float = 200.0

    def __post_init__(self) -> None:
        for name in ("max_speed", "track_width", "radius"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a number more than 0, not {value!r}")

    def move(self, pose: Pose, left_power: float, right_power: float, seconds: float) -> Pose:
        """Return the pose after ``seconds`` at the given wheel powers (-1 to 1)."""
        v_left = max(-1.0, min(1.0, left_power)) * self.max_speed
        v_right = max(-1.0, min(1.0, right_power)) * self.max_speed
        speed = (v_left + v_right) / 2
        turn = (v_right - v_left) / self.track_width
        if abs(turn) < 1e-9:
            return Pose(
                pose.x + speed * seconds * math.cos(pose.heading),
                pose.y + speed * seconds * math.sin(pose.heading),
                pose.heading,
            )
        heading = pose.heading + turn * seconds
        radius = speed / turn
        return Pose(
            pose.x + radius * (math.sin(heading) - math.sin(pose.heading)),
            pose.y - radius * (math.cos(heading) - math.cos(pose.heading)),
            math.remainder(heading, math.tau),
        )


@dataclass
class SimulatedWorld:
    """The arena, the robot's pose and drive, and the camera on the robot.

    Part of the simulated kit (``kit.world``). :meth:`update` moves the robot by the time
    passed since the last update, at the motor powers it saw then.

    :param arena: the arena.
    :param pose: where the robot starts.
    :param drive: the drive model.
    :param camera_height: height of the camera's lens above the floor, mm.
    :param camera_forward: how far in front of the robot's centre the camera is, mm (by
        default at the front edge of the robot, so the camera's distance to a wall is the
        gap between the robot and the wall).
    :param camera_left: how far to the left of the robot's centre the camera is, mm.
    :param camera_angle: which way the camera looks, radians anticlockwise from the
        robot's forward direction (it always looks level).
    """

    arena: Arena = field(default_factory=Arena.standard)
    pose: Pose = field(default_factory=lambda: Pose(2875.0, 1000.0, math.pi / 2))
    drive: DifferentialDrive = field(default_factory=DifferentialDrive)
    camera_height: float = 200.0
    camera_forward: float = 200.0
    camera_left: float = 0.0
    camera_angle: float = 0.0
    _powers: tuple[float, float] = (0.0, 0.0)
    _time: float | None = None

    def update(self, now: float, left_power: float, right_power: float) -> Pose:
        """Move the robot to time ``now`` (seconds), then hold the powers given.

        The powers held since the last update apply to the time that passed.
        """
        if self._time is not None and now > self._time:
            moved = self.drive.move(self.pose, *self._powers, now - self._time)
            self.pose = self._inside(moved)
        self._time = now if self._time is None else max(now, self._time)
        self._powers = (left_power, right_power)
        return self.pose

    def _inside(self, pose: Pose) -> Pose:
        r = self.drive.radius
        return Pose(
            min(max(pose.x, r), self.arena.width - r),
            min(max(pose.y, r), self.arena.length - r),
            pose.heading,
        )

    def place_robot(self, pose: Pose) -> None:
        """Put the robot at ``pose`` (the motors' powers are kept)."""
        self.pose = self._inside(pose)

    def camera_position(self) -> tuple[float, float, float]:
        """Where the camera's lens is in the world, mm."""
        p = self.pose
        c, s = math.cos(p.heading), math.sin(p.heading)
        return (
            p.x + self.camera_forward * c - self.camera_left * s,
            p.y + self.camera_forward * s + self.camera_left * c,
            self.camera_height,
        )

    def camera_heading(self) -> float:
        """Which way the camera looks in the world, radians from east."""
        return self.pose.heading + self.camera_angle

    def camera_mount(self) -> CameraMount:
        """Where the camera is on the robot, as :func:`~j5aio.vision.locate.locate` takes it."""
        from j5aio.vision.locate import CameraMount

        return CameraMount(
            forward=self.camera_forward,
            left=self.camera_left,
            angle=math.remainder(self.camera_angle, math.tau),
        )
