"""Where the robot is, from the wall markers in one picture.

::

    from j5aio.vision.arena_map import ArenaMap
    from j5aio.vision.locate import CameraMount, locate

    ARENA = ArenaMap.standard()
    MOUNT = CameraMount(forward=200)        # the camera is 200 mm in front of the centre

    where = locate(await robot.camera.see(), ARENA, MOUNT)
    if where is not None:
        print(where.x, where.y, where.heading, "±", where.position_error, "mm")

**How.** Each wall marker seen gives three measurements from the camera: its distance
and bearing across the floor, and which way its face points (from its orientation).
One marker alone fixes the robot (its facing gives the heading, its distance and bearing
then the position); two or more are combined by weighted least squares (Gauss-Newton on
the robot's x, y and heading), where the bearings, the most accurate measurements, tie
the heading down across the markers. Each measurement is weighted by how well a marker
of its size in the picture is measured, and the result's uncertainty comes from the same
weights (made larger when the markers agree less well than they should).

**Wrong markers.** A marker whose id is not on a wall (a token's, or a stray one) is left
out. So is one that disagrees with the others: two markers agree when the distance
between them as seen matches the map's, and when the heading that the pair gives agrees
with the heading that each one's facing gives. The largest set of markers that all agree
with each other is used; when it is a single marker among others that disagree with it,
nothing says which one is right, and the answer is ``None`` (unless a ``prior`` estimate,
as :mod:`j5aio.vision.track` keeps, picks the hypothesis nearest to it). The result lists
the markers used and those left out, with the reason.

The camera is taken to be level across (no roll); a camera tilted up or down is allowed
for by the ``tilt`` of its :class:`CameraMount`.

No optional library is needed here: the function takes any list of markers with the
fields of :class:`~j5aio.vision.markers.Marker`, from any camera.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Protocol

from j5aio.components._checks import check_number
from j5aio.vision.arena_map import ArenaMap, WallMarker
from j5aio.vision.geometry import rotation_from_orientation
from j5aio.vision.markers import Orientation, PixelCoordinates, Position

__all__ = [
    "CameraMount",
    "Location",
    "MarkerLike",
    "PoseLike",
    "RejectedMarker",
    "locate",
    "marker_position",
]

#: A marker under this many pixels wide is not trusted alone to place the robot.
MIN_PIXELS_ALONE = 12.0

#: A marker under this many pixels wide is not used at all.
MIN_PIXELS = 6.0

# The measurement noise model (one standard deviation), in terms of the marker's width in
# the picture, ``pixels``: its distance is measured to RANGE_NOISE / pixels of itself,
# its bearing to BEARING_NOISE radians, its facing to FACING_NOISE / pixels radians.
# Measured on the simulated camera (bench/bench_locate.py) and then doubled, for the
# blur, the noise and the calibration error of a real camera.
RANGE_NOISE = 0.25
RANGE_FLOOR = 0.002
BEARING_NOISE = math.radians(0.08)
FACING_NOISE = 0.5
FACING_FLOOR = math.radians(0.5)

# When one marker's measurement of another (distance between them as seen, heading of the
# pair) is this many standard deviations from the map's, the two disagree.
_AGREEMENT_SIGMAS = 4.0
# Margins added to those tests, for what the noise model misses.
_SEPARATION_MARGIN = 60.0  # mm
_HEADING_MARGIN = math.radians(8.0)

# A marker's facing this many standard deviations off the fit of two or more markers is
# ignored (a small marker's orientation can be wrong by tens of degrees, when the detector
# takes the mirror image of its pose); its distance and bearing are still used.
_FACING_OUTLIER_SIGMAS = 5.0

# How far outside the arena (mm) a robot's centre may seem to be and still be believed.
_OUTSIDE_MARGIN = 250.0

_ITERATIONS = 8

Matrix = list[list[float]]


class MarkerLike(Protocol):
    """What :func:`locate` reads of a marker: any camera's markers with these fields will do."""

    @property
    def id(self) -> int:
        """Its AprilTag 36h11 id."""

    @property
    def size(self) -> float:
        """The size the camera took it to be (mm); distances scale with it."""

    @property
    def position(self) -> Position:
        """Distance (mm) and angles (radians) from the camera."""

    @property
    def orientation(self) -> Orientation:
        """Yaw, pitch and roll (radians), all 0 for a marker facing the camera squarely."""

    @property
    def pixel_corners(self) -> Sequence[PixelCoordinates]:
        """Its four corners on the picture (for its size in pixels)."""


class PoseLike(Protocol):
    """A robot's pose: a :class:`Location`, a tracker's estimate, or anything with these."""

    @property
    def x(self) -> float:
        """mm, in the arena's frame."""

    @property
    def y(self) -> float:
        """mm, in the arena's frame."""

    @property
    def heading(self) -> float:
        """Radians anticlockwise from the arena's x axis."""


@dataclass(frozen=True)
class CameraMount:
    """Where the camera is on the robot, so that the robot's centre is located, not the camera.

    :param forward: how far in front of the robot's centre the camera's lens is, mm.
    :param left: how far to the left of the centre, mm.
    :param angle: which way the camera looks, radians anticlockwise (to the left) from
        the robot's forward direction.
    :param tilt: how far the camera looks up (negative: down), radians.
    :raises TypeError: a value is not a number.
    :raises ValueError: a value is not finite, or an angle is beyond a half turn.
    """

    forward: float = 0.0
    left: float = 0.0
    angle: float = 0.0
    tilt: float = 0.0

    def __post_init__(self) -> None:
        for name in ("forward", "left"):
            check_number(
                getattr(self, name), name=f"the camera's {name} offset", low=-1e6, high=1e6,
                allowed="a number of mm (-1e6 to 1e6)",
            )
        check_number(
            self.angle, name="the camera's angle", low=-math.pi, high=math.pi,
            allowed="a number of radians from -pi to pi",
        )
        check_number(
            self.tilt, name="the camera's tilt", low=-math.pi / 2, high=math.pi / 2,
            allowed="a number of radians from -pi/2 to pi/2",
        )


@dataclass(frozen=True)
class RejectedMarker:
    """A marker seen but not used, and why."""

    id: int
    reason: str


@dataclass(frozen=True)
class Location:
    """Where the robot is: its centre in the arena's frame and its heading.

    :param x: mm.
    :param y: mm.
    :param heading: radians anticlockwise from the arena's x axis, -pi to pi.
    :param position_error: the uncertainty of the position, mm: the root of the sum of
        the variances of x and y (about two in three estimates are nearer than this).
    :param heading_error: the uncertainty (one standard deviation) of the heading, radians.
    :param used: the ids of the markers the estimate comes from.
    :param rejected: the markers seen and left out, with the reason.
    :param covariance: the 3x3 covariance of (x, y, heading), mm and radians.
    """

    x: float
    y: float
    heading: float
    position_error: float
    heading_error: float
    used: tuple[int, ...]
    rejected: tuple[RejectedMarker, ...] = ()
    covariance: tuple[tuple[float, float, float], ...] = ()

    def __str__(self) -> str:
        return (
            f"({self.x:.0f}, {self.y:.0f}) mm ± {self.position_error:.0f}, heading "
            f"{math.degrees(self.heading):.1f}° ± {math.degrees(self.heading_error):.1f}°, "
            f"from marker{'s' if len(self.used) != 1 else ''} "
            + ", ".join(str(i) for i in self.used)
        )


@dataclass(frozen=True)
class _Sighting:
    """One wall marker as seen, reduced to the floor's plane, with its noise."""

    wall: WallMarker
    range: float  # mm, across the floor from the camera
    bearing: float  # radians, anticlockwise from the camera's forward direction
    facing: float  # radians: the marker's outward normal, from the camera's forward
    sigma_range: float
    sigma_bearing: float
    sigma_facing: float
    pixels: float
    use_facing: bool = True  # False: its facing was far off the fit, and is ignored

    def camera_heading(self) -> float:
        """The camera's heading that this marker's facing alone gives."""
        return _wrap(self.wall.facing - self.facing)


def _wrap(angle: float) -> float:
    return math.remainder(angle, math.tau)


def _pixels(marker: MarkerLike) -> float:
    corners = list(marker.pixel_corners)
    if len(corners) != 4:
        return math.nan
    return sum(math.dist(corners[i], corners[(i + 1) % 4]) for i in range(4)) / 4


def _sighting(marker: MarkerLike, wall: WallMarker, tilt: float) -> _Sighting:
    distance, horizontal, vertical = marker.position
    # The camera's frame: forward, left, up; scaled if the camera took another size.
    scale = wall.size / marker.size if marker.size > 0 else 1.0
    forward = distance * scale / math.sqrt(1 + math.tan(horizontal) ** 2 + math.tan(vertical) ** 2)
    left = -forward * math.tan(horizontal)
    up = forward * math.tan(vertical)
    cos_t, sin_t = math.cos(tilt), math.sin(tilt)
    level_forward = forward * cos_t - up * sin_t
    # The marker's outward normal (OpenCV's z axis of the marker points into its face).
    rotation = rotation_from_orientation(Orientation(*marker.orientation))
    n_right, n_down, n_forward = -rotation[0][2], -rotation[1][2], -rotation[2][2]
    n_level_forward = n_forward * cos_t - (-n_down) * sin_t
    pixels = _pixels(marker)
    span = pixels if math.isfinite(pixels) and pixels > 0 else math.inf
    range_ = math.hypot(level_forward, left)
    return _Sighting(
        wall,
        range_,
        math.atan2(left, level_forward),
        math.atan2(-n_right, n_level_forward),
        range_ * max(RANGE_NOISE / span, RANGE_FLOOR),
        BEARING_NOISE,
        max(FACING_NOISE / span, FACING_FLOOR),
        pixels,
    )


# --------------------------------------------------------------------------- the model


def _camera(pose: Sequence[float], mount: CameraMount) -> tuple[float, float, float]:
    x, y, heading = pose
    c, s = math.cos(heading), math.sin(heading)
    return (
        x + mount.forward * c - mount.left * s,
        y + mount.forward * s + mount.left * c,
        heading + mount.angle,
    )


def _pose_from_camera(cx: float, cy: float, camera_heading: float, mount: CameraMount) -> tuple[
    float, float, float
]:
    heading = _wrap(camera_heading - mount.angle)
    c, s = math.cos(heading), math.sin(heading)
    return (
        cx - mount.forward * c + mount.left * s,
        cy - mount.forward * s - mount.left * c,
        heading,
    )


def _single_pose(sighting: _Sighting, mount: CameraMount) -> tuple[float, float, float]:
    """The pose that one marker's distance, bearing and facing give."""
    heading = sighting.camera_heading()
    direction = heading + sighting.bearing
    cx = sighting.wall.x - sighting.range * math.cos(direction)
    cy = sighting.wall.y - sighting.range * math.sin(direction)
    return _pose_from_camera(cx, cy, heading, mount)


def _residuals(
    pose: Sequence[float], sightings: Sequence[_Sighting], mount: CameraMount
) -> tuple[list[float], Matrix]:
    """Weighted residuals and the Jacobian of the weighted predictions in the pose.

    A residual is (measured - predicted) / sigma; the Jacobian is that of
    predicted / sigma in (x, y, heading).
    """
    heading = pose[2]
    cx, cy, camera_heading = _camera(pose, mount)
    c, s = math.cos(heading), math.sin(heading)
    # d(camera x, camera y) / d(heading)
    dcx = -mount.forward * s - mount.left * c
    dcy = mount.forward * c - mount.left * s
    rows: list[float] = []
    jacobian: Matrix = []
    for seen in sightings:
        dx, dy = seen.wall.x - cx, seen.wall.y - cy
        r2 = max(dx * dx + dy * dy, 1e-6)
        r = math.sqrt(r2)
        # range
        rows.append((seen.range - r) / seen.sigma_range)
        jacobian.append(
            [-dx / r / seen.sigma_range, -dy / r / seen.sigma_range,
             -(dx * dcx + dy * dcy) / r / seen.sigma_range]
        )
        # bearing
        predicted = math.atan2(dy, dx) - camera_heading
        rows.append(_wrap(seen.bearing - predicted) / seen.sigma_bearing)
        jacobian.append(
            [dy / r2 / seen.sigma_bearing, -dx / r2 / seen.sigma_bearing,
             ((dy * dcx - dx * dcy) / r2 - 1) / seen.sigma_bearing]
        )
        # facing
        if seen.use_facing:
            predicted = seen.wall.facing - camera_heading
            rows.append(_wrap(seen.facing - predicted) / seen.sigma_facing)
            jacobian.append([0.0, 0.0, -1.0 / seen.sigma_facing])
        else:
            rows.append(0.0)
            jacobian.append([0.0, 0.0, 0.0])
    return rows, jacobian


def _solve3(a: Matrix, b: Sequence[float]) -> list[float] | None:
    """Solve a 3x3 system by Gaussian elimination with pivoting; ``None`` if singular."""
    m = [[*a[i], b[i]] for i in range(3)]
    for col in range(3):
        pivot = max(range(col, 3), key=lambda r: abs(m[r][col]))
        if abs(m[pivot][col]) < 1e-12:
            return None
        m[col], m[pivot] = m[pivot], m[col]
        for r in range(3):
            if r != col:
                f = m[r][col] / m[col][col]
                for k in range(col, 4):
                    m[r][k] -= f * m[col][k]
    return [m[i][3] / m[i][i] for i in range(3)]


def _inverse3(a: Matrix) -> Matrix | None:
    columns = []
    for i in range(3):
        column = _solve3(a, [1.0 if j == i else 0.0 for j in range(3)])
        if column is None:
            return None
        columns.append(column)
    return [[columns[j][i] for j in range(3)] for i in range(3)]


def _normal_equations(rows: Sequence[float], jacobian: Matrix) -> tuple[Matrix, list[float]]:
    jtj = [[0.0] * 3 for _ in range(3)]
    jtr = [0.0] * 3
    for r, row in zip(rows, jacobian, strict=True):
        for i in range(3):
            jtr[i] += row[i] * r
            for j in range(3):
                jtj[i][j] += row[i] * row[j]
    return jtj, jtr


@dataclass(frozen=True)
class _Fit:
    pose: tuple[float, float, float]
    covariance: Matrix
    chi2: float
    rows: list[float]


def _fit(
    start: Sequence[float], sightings: Sequence[_Sighting], mount: CameraMount
) -> _Fit | None:
    pose = [float(v) for v in start]
    for _ in range(_ITERATIONS):
        rows, jacobian = _residuals(pose, sightings, mount)
        jtj, jtr = _normal_equations(rows, jacobian)
        step = _solve3(jtj, jtr)
        if step is None:
            return None
        pose = [pose[0] + step[0], pose[1] + step[1], _wrap(pose[2] + step[2])]
        if abs(step[0]) + abs(step[1]) < 0.01 and abs(step[2]) < 1e-6:
            break
    rows, jacobian = _residuals(pose, sightings, mount)
    jtj, _ = _normal_equations(rows, jacobian)
    covariance = _inverse3(jtj)
    if covariance is None:  # pragma: no cover - the facing rows keep it invertible
        return None
    return _Fit((pose[0], pose[1], pose[2]), covariance, sum(r * r for r in rows), rows)


# --------------------------------------------------------------------------- agreement


def _agree(a: _Sighting, b: _Sighting) -> bool:
    """Whether two markers' measurements are consistent with the map's places for them."""
    ax, ay = a.range * math.cos(a.bearing), a.range * math.sin(a.bearing)
    bx, by = b.range * math.cos(b.bearing), b.range * math.sin(b.bearing)
    seen_dx, seen_dy = bx - ax, by - ay
    seen_separation = math.hypot(seen_dx, seen_dy)
    map_dx, map_dy = b.wall.x - a.wall.x, b.wall.y - a.wall.y
    map_separation = math.hypot(map_dx, map_dy)
    # Each end's position across the line of sight is known to range * sigma_bearing.
    spread = math.sqrt(
        a.sigma_range**2 + b.sigma_range**2
        + (a.range * a.sigma_bearing) ** 2 + (b.range * b.sigma_bearing) ** 2
    )
    tolerance = _AGREEMENT_SIGMAS * spread + _SEPARATION_MARGIN
    if abs(seen_separation - map_separation) > tolerance:
        return False
    if map_separation < 1.0:  # pragma: no cover - the map has each id once, in one place
        return True
    pair_heading = math.atan2(map_dy, map_dx) - math.atan2(seen_dy, seen_dx)
    heading_tolerance = _HEADING_MARGIN + math.atan2(tolerance, map_separation)
    # One facing that agrees is enough: a small marker's facing can be far off (see
    # _FACING_OUTLIER_SIGMAS) while its distance and bearing are good.
    return any(
        abs(_wrap(pair_heading - s.camera_heading()))
        <= heading_tolerance + _AGREEMENT_SIGMAS * s.sigma_facing
        for s in (a, b)
    )


def _largest_agreeing(sightings: Sequence[_Sighting]) -> list[list[int]]:
    """Every largest set of sightings (indices) that all agree with each other."""
    count = len(sightings)
    agrees = [
        {j for j in range(count) if j != i and _agree(sightings[i], sightings[j])}
        for i in range(count)
    ]
    best: list[list[int]] = []

    def grow(chosen: list[int], candidates: list[int]) -> None:
        nonlocal best
        if len(chosen) + len(candidates) < (len(best[0]) if best else 0):
            return
        if not candidates:
            if not best or len(chosen) > len(best[0]):
                best = [chosen]
            elif len(chosen) == len(best[0]):
                best.append(chosen)
            return
        first, rest = candidates[0], candidates[1:]
        grow([*chosen, first], [c for c in rest if c in agrees[first]])
        grow(chosen, rest)

    grow([], list(range(count)))
    return best


# --------------------------------------------------------------------------- locate


def _pose_of(prior: Location | Sequence[float]) -> tuple[float, float, float]:
    if isinstance(prior, Location):
        return (prior.x, prior.y, prior.heading)
    x, y, heading = prior
    return (float(x), float(y), float(heading))


def _distance_to(
    pose: Sequence[float], prior: tuple[float, float, float], sighting_range: float
) -> float:
    """How far a pose is from the prior, the heading counted at the marker's distance."""
    return math.hypot(pose[0] - prior[0], pose[1] - prior[1]) + sighting_range * abs(
        _wrap(pose[2] - prior[2])
    )


def locate(
    markers: Iterable[MarkerLike],
    arena_map: ArenaMap,
    mount: CameraMount | None = None,
    *,
    prior: Location | Sequence[float] | None = None,
) -> Location | None:
    """Work out where the robot is from the markers of one picture.

    :param markers: what the camera saw (``await camera.see()``): markers with a pose.
    :param arena_map: the arena: where each wall marker is.
    :param mount: where the camera is on the robot; by default at the robot's centre,
        looking forwards.
    :param prior: where the robot is believed to be (a :class:`Location` or
        ``(x, y, heading)``), used only to choose between markers that disagree with no
        majority; :class:`~j5aio.vision.track.PositionTracker` passes its estimate.
    :returns: the robot's position and heading with their uncertainty, or ``None`` when
        the markers cannot tell: no wall marker with a pose is seen, a lone marker is too
        small in the picture to trust, the markers disagree with no majority, or the
        answer is outside the arena.
    :raises TypeError: ``arena_map`` is not an :class:`~j5aio.vision.arena_map.ArenaMap`.
    """
    if not isinstance(arena_map, ArenaMap):
        raise TypeError(
            f"arena_map must be an ArenaMap (j5aio.vision.arena_map); got {arena_map!r}"
        )
    mount = CameraMount() if mount is None else mount
    rejected: list[RejectedMarker] = []
    sightings: list[_Sighting] = []
    for marker in markers:
        wall = arena_map.wall_marker(marker.id)
        if wall is None:
            reason = "a token" if marker.id in arena_map.token_sizes else "not on the walls"
            rejected.append(RejectedMarker(marker.id, reason))
            continue
        if not math.isfinite(marker.position.distance):
            rejected.append(RejectedMarker(marker.id, "no pose (the camera has no calibration)"))
            continue
        sighting = _sighting(marker, wall, mount.tilt)
        if sighting.pixels < MIN_PIXELS:
            rejected.append(RejectedMarker(marker.id, "too small in the picture"))
            continue
        sightings.append(sighting)
    if not sightings:
        return None
    groups = _largest_agreeing(sightings)
    if len(groups) > 1:
        # Several sets tie: the markers in all of them agree with each other; when there
        # are two or more of those, they are the answer (the disputed ones are left out).
        core = sorted(set(groups[0]).intersection(*groups[1:]))
        if len(core) >= 2:
            groups = [core]
    prior_pose = None if prior is None else _pose_of(prior)
    if len(groups) > 1 or (len(groups[0]) == 1 and len(sightings) > 1):
        # No majority: only a prior, or the arena's walls, can choose.
        candidates = [
            g for g in groups
            if arena_map.contains(*_single_pose(sightings[g[0]], mount)[:2], _OUTSIDE_MARGIN)
        ]
        if len(candidates) > 1 and prior_pose is not None:
            candidates = [
                min(
                    candidates,
                    key=lambda g: _distance_to(
                        _single_pose(sightings[g[0]], mount), prior_pose, sightings[g[0]].range
                    ),
                )
            ]
        if len(candidates) != 1:
            return None
        groups = candidates
    chosen = groups[0]
    for i, sighting in enumerate(sightings):
        if i not in chosen:
            rejected.append(RejectedMarker(sighting.wall.id, "disagrees with the others"))
    used = [sightings[i] for i in chosen]
    if len(used) == 1 and used[0].pixels < MIN_PIXELS_ALONE:
        rejected.append(RejectedMarker(used[0].wall.id, "too small in the picture to use alone"))
        return None
    start = _single_pose(max(used, key=lambda s: s.pixels), mount)
    fit = _fit(start, used, mount)
    if fit is None:  # pragma: no cover - only for degenerate input
        return None
    while len(used) >= 2:
        far_off = {
            i for i, s in enumerate(used)
            if s.use_facing and abs(fit.rows[3 * i + 2]) > _FACING_OUTLIER_SIGMAS
        }
        if not far_off:
            break
        used = [
            dataclasses.replace(s, use_facing=False) if i in far_off else s
            for i, s in enumerate(used)
        ]
        refit = _fit(fit.pose, used, mount)
        if refit is None:  # pragma: no cover - the bearings of two markers fix the heading
            break
        fit = refit
    dof = 2 * len(used) + sum(s.use_facing for s in used) - 3
    scale = max(1.0, fit.chi2 / dof) if dof > 0 else 1.0
    covariance = [[v * scale for v in row] for row in fit.covariance]
    x, y, heading = fit.pose
    position_error = math.sqrt(max(covariance[0][0] + covariance[1][1], 0.0))
    if not arena_map.contains(x, y, _OUTSIDE_MARGIN + 2 * position_error):
        return None
    return Location(
        x,
        y,
        heading,
        position_error,
        math.sqrt(max(covariance[2][2], 0.0)),
        tuple(s.wall.id for s in used),
        tuple(rejected),
        tuple((row[0], row[1], row[2]) for row in covariance),
    )


def marker_position(
    marker: MarkerLike, robot: PoseLike, mount: CameraMount | None = None
) -> tuple[float, float]:
    """Where in the arena a marker seen from the robot is: the (x, y) of its centre, mm.

    For a token: ``marker_position(marker, where, MOUNT)`` with the robot's pose
    ``where`` (from :func:`locate` or a tracker) says where the token's face is.

    :param marker: a marker with a pose, as the camera reported it.
    :param robot: the robot's pose when the picture was taken.
    :param mount: where the camera is on the robot (by default at its centre, forwards).
    :raises ValueError: the marker has no pose (the camera has no calibration).
    """
    mount = CameraMount() if mount is None else mount
    distance, horizontal, vertical = marker.position
    if not math.isfinite(distance):
        raise ValueError(f"marker {marker.id} has no pose: the camera has no calibration")
    forward = distance / math.sqrt(1 + math.tan(horizontal) ** 2 + math.tan(vertical) ** 2)
    up = forward * math.tan(vertical)
    level_forward = forward * math.cos(mount.tilt) - up * math.sin(mount.tilt)
    left = -forward * math.tan(horizontal)
    cx, cy, camera_heading = _camera((robot.x, robot.y, robot.heading), mount)
    c, s = math.cos(camera_heading), math.sin(camera_heading)
    return (cx + c * level_forward - s * left, cy + s * level_forward + c * left)
