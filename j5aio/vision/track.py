"""A running estimate of where the robot is, carried between pictures.

::

    tracker = PositionTracker(robot.camera, ArenaMap.standard(), CameraMount(forward=200))
    await tracker.update()                  # look once, and fold what is seen in
    tracker.set_motion(speed=400)           # the program says it drives forwards at 400 mm/s
    where = tracker.estimate()              # where it is now: no picture needed
    print(where.x, where.y, where.age)      # age: seconds since markers were last seen

The estimate is an extended Kalman filter on the robot's x, y and heading. Each picture
with wall markers gives a fix (:func:`~j5aio.vision.locate.locate`), which is weighed
against the estimate by both their uncertainties. Between fixes the estimate moves as
the program says the robot moves (:meth:`PositionTracker.moved` for a distance driven and
an angle turned, :meth:`PositionTracker.set_motion` for a speed held), and its uncertainty
grows with the distance; when the program says nothing, the robot is taken to stand
still, give or take a wander of :attr:`PositionTracker.wander` mm a second (a random
walk), so a stale estimate says how unsure it has become.

A fix far outside what the estimate allows (a misread marker that
:func:`~j5aio.vision.locate.locate` could not catch alone) is set aside; when three fixes in
a row are set aside, the robot must have been moved: the estimate starts again from the
newest fix.

Through the sync facade (``from j5aio.sync import PositionTracker``) the same calls block
instead of being awaited. No optional library is needed here.
"""

from __future__ import annotations

import math
import time
import weakref
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import anyio

from j5aio.components._checks import check_number
from j5aio.components.marker_camera import MarkerCamera
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.locate import CameraMount, Location, MarkerLike, locate

__all__ = ["Estimate", "PositionTracker", "latest_estimate"]

Matrix = list[list[float]]

#: A fix whose squared Mahalanobis distance from the estimate is more than this is set
#: aside (three degrees of freedom: 0.1 % of good fixes go beyond 16.3).
GATE = 16.3

#: After this many fixes in a row are set aside, the estimate restarts from the newest.
RESTART_AFTER = 3


@dataclass(frozen=True)
class Estimate:
    """Where the tracker believes the robot is, at a moment.

    :param x: mm, in the arena's frame.
    :param y: mm.
    :param heading: radians anticlockwise from the arena's x axis, -pi to pi.
    :param position_error: the uncertainty of the position, mm (as in
        :class:`~j5aio.vision.locate.Location`).
    :param heading_error: the uncertainty of the heading, radians.
    :param age: seconds since the last fix from markers was folded in (the estimate has
        been carried by dead reckoning since then).
    :param time: the tracker's clock time the estimate is for, seconds.
    :param last_fix: the last fix folded in.
    """

    x: float
    y: float
    heading: float
    position_error: float
    heading_error: float
    age: float
    time: float
    last_fix: Location

    def __str__(self) -> str:
        return (
            f"({self.x:.0f}, {self.y:.0f}) mm ± {self.position_error:.0f}, heading "
            f"{math.degrees(self.heading):.1f}° ± {math.degrees(self.heading_error):.1f}°, "
            f"{self.age:.1f} s since markers were seen"
        )


def _wrap(angle: float) -> float:
    return math.remainder(angle, math.tau)


def _mul(a: Matrix, b: Matrix) -> Matrix:
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def _t(a: Matrix) -> Matrix:
    return [[a[j][i] for j in range(3)] for i in range(3)]


def _add(a: Matrix, b: Matrix) -> Matrix:
    return [[a[i][j] + b[i][j] for j in range(3)] for i in range(3)]


def _inverse(a: Matrix) -> Matrix | None:
    (a11, a12, a13), (a21, a22, a23), (a31, a32, a33) = a
    det = (
        a11 * (a22 * a33 - a23 * a32)
        - a12 * (a21 * a33 - a23 * a31)
        + a13 * (a21 * a32 - a22 * a31)
    )
    if abs(det) < 1e-30:
        return None
    return [
        [(a22 * a33 - a23 * a32) / det, (a13 * a32 - a12 * a33) / det,
         (a12 * a23 - a13 * a22) / det],
        [(a23 * a31 - a21 * a33) / det, (a11 * a33 - a13 * a31) / det,
         (a13 * a21 - a11 * a23) / det],
        [(a21 * a32 - a22 * a31) / det, (a12 * a31 - a11 * a32) / det,
         (a11 * a22 - a12 * a21) / det],
    ]


def _diagonal(a: float, b: float, c: float) -> Matrix:
    return [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]]


def _relative(start: Sequence[float], end: Sequence[float]) -> tuple[float, float, float]:
    """The move from ``start`` to ``end`` in ``start``'s frame: forward, left, turn."""
    c, s = math.cos(start[2]), math.sin(start[2])
    dx, dy = end[0] - start[0], end[1] - start[1]
    return (c * dx + s * dy, -s * dx + c * dy, _wrap(end[2] - start[2]))


def _compose(pose: Sequence[float], move: Sequence[float]) -> list[float]:
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return [
        pose[0] + c * move[0] - s * move[1],
        pose[1] + s * move[0] + c * move[1],
        _wrap(pose[2] + move[2]),
    ]


# The tracker that made an estimate last, and that estimate (for the live view).
_latest: tuple[weakref.ref[PositionTracker], Estimate] | None = None


def latest_estimate() -> Estimate | None:
    """The estimate that a tracker of this program made last, while that tracker exists.

    The live view shows it beside the simulated robot's true pose. It is the last
    estimate asked for or made by a picture: it does not move on by itself.
    """
    latest = _latest
    if latest is None or latest[0]() is None:
        return None
    return latest[1]


@dataclass
class _State:
    time: float
    mean: list[float]
    covariance: Matrix


class PositionTracker:
    """Keeps an estimate of the robot's pose from its camera's markers and its own motion.

    :param camera: the robot's marker camera (``robot.camera``), looked through by
        :meth:`update`; ``None`` for a tracker fed only by :meth:`observe`.
    :param arena_map: the arena's wall markers.
    :param mount: where the camera is on the robot (by default at its centre, forwards).
    :param wander: how fast the robot may move unseen while the program says nothing of
        its motion, mm/s (the estimate's uncertainty grows by so much a second, as a
        random walk); 0 trusts that the robot stands still.
    :param slip: the fraction by which the real motion may differ from what the program
        says (wheels slip, speeds are guessed): the uncertainty grows by this fraction of
        the distance driven and of the angle turned since the last fix.
    :param clock: the clock, in seconds (``time.monotonic`` by default).
    :raises TypeError: ``arena_map`` is not an ArenaMap, or ``camera`` not a MarkerCamera.
    :raises ValueError: ``wander`` or ``slip`` is negative.
    """

    def __init__(
        self,
        camera: MarkerCamera | None,
        arena_map: ArenaMap,
        mount: CameraMount | None = None,
        *,
        wander: float = 300.0,
        slip: float = 0.1,
        clock: Callable[[], float] | None = None,
    ) -> None:
        if camera is not None and not isinstance(camera, MarkerCamera):
            raise TypeError(f"camera must be a MarkerCamera (robot.camera) or None; got {camera!r}")
        if not isinstance(arena_map, ArenaMap):
            raise TypeError(
                f"arena_map must be an ArenaMap (j5aio.vision.arena_map); got {arena_map!r}"
            )
        #: How fast (mm/s) the robot may move unseen when the program says nothing.
        self.wander = check_number(
            wander, name="wander", low=0.0, high=1e6, allowed="a speed in mm/s, 0 or more"
        )
        #: The fraction by which real motion may differ from what the program says.
        self.slip = check_number(slip, name="slip", low=0.0, high=10.0, allowed="0 or more")
        self._camera = camera
        self._map = arena_map
        self._mount = CameraMount() if mount is None else mount
        self._clock = time.monotonic if clock is None else clock
        self._state: _State | None = None
        self._last_fix: Location | None = None
        self._fix_time = 0.0
        self._speed = 0.0
        self._turn_rate = 0.0
        self._set_aside: list[Location] = []
        # The distance driven and angle turned (as the program said) since the last fix.
        self._travelled = 0.0
        self._turned = 0.0

    # ------------------------------------------------------------------ what it knows

    @property
    def arena_map(self) -> ArenaMap:
        """The arena the robot is located in."""
        return self._map

    @property
    def mount(self) -> CameraMount:
        """Where the camera is on the robot."""
        return self._mount

    def estimate(self) -> Estimate | None:
        """Where the robot is now, carried on from the last fix; ``None`` before any fix."""
        now = self._clock()
        self._predict(now)
        return self._estimate()

    def _estimate(self) -> Estimate | None:
        state, fix = self._state, self._last_fix
        if state is None or fix is None:
            return None
        cov = state.covariance
        estimate = Estimate(
            state.mean[0],
            state.mean[1],
            state.mean[2],
            math.sqrt(max(cov[0][0] + cov[1][1], 0.0)),
            math.sqrt(max(cov[2][2], 0.0)),
            max(0.0, state.time - self._fix_time),
            state.time,
            fix,
        )
        global _latest
        _latest = (weakref.ref(self), estimate)
        return estimate

    # ------------------------------------------------------------------ motion

    def moved(self, forward: float, turned: float = 0.0, *, left: float = 0.0) -> None:
        """Say that the robot has just moved: ``forward`` mm, turning ``turned`` radians.

        The move is taken along an arc (a differential drive's), in the robot's frame as
        it was; ``left`` is a sideways move, mm (for a robot that can). Its uncertainty is
        :attr:`slip` of it.

        :raises TypeError: a value is not a number.
        :raises ValueError: a value is not finite.
        """
        forward = check_number(forward, name="forward", low=-1e7, high=1e7, allowed="mm")
        turned = check_number(turned, name="turned", low=-1e4, high=1e4, allowed="radians")
        left = check_number(left, name="left", low=-1e7, high=1e7, allowed="mm")
        now = self._clock()
        self._predict(now)
        if self._state is not None:
            self._apply_move(self._state, forward, left, turned)

    def set_motion(self, speed: float = 0.0, turn_rate: float = 0.0) -> None:
        """Say how the robot drives from now on (both 0: it stands still).

        It drives forwards at ``speed`` mm/s, turning anticlockwise at ``turn_rate``
        rad/s. Until the next call the estimate moves so, with :attr:`slip` of uncertainty.

        :raises TypeError: a value is not a number.
        :raises ValueError: a value is not finite.
        """
        speed = check_number(speed, name="speed", low=-1e6, high=1e6, allowed="mm/s")
        turn_rate = check_number(
            turn_rate, name="turn_rate", low=-1e3, high=1e3, allowed="rad/s"
        )
        self._predict(self._clock())
        self._speed, self._turn_rate = speed, turn_rate

    def _apply_move(self, state: _State, forward: float, left: float, turned: float) -> None:
        heading = state.mean[2]
        # An arc: the chord is taken along the mean heading of the move.
        chord_heading = heading + turned / 2
        factor = math.sin(turned / 2) / (turned / 2) if abs(turned) > 1e-9 else 1.0
        along, across = forward * factor, left * factor
        c, s = math.cos(chord_heading), math.sin(chord_heading)
        state.mean = [
            state.mean[0] + c * along - s * across,
            state.mean[1] + s * along + c * across,
            _wrap(heading + turned),
        ]
        jacobian = [
            [1.0, 0.0, -s * along - c * across],
            [0.0, 1.0, c * along - s * across],
            [0.0, 0.0, 1.0],
        ]
        # A wrong speed is wrong all along: the error of the motion said since the last fix
        # grows with its whole length, however many pieces it was said in.
        slip = self.slip
        before_distance, before_turn = self._travelled, self._turned
        self._travelled += math.hypot(forward, left)
        self._turned += abs(turned)
        grown_distance = slip**2 * (self._travelled**2 - before_distance**2)
        grown_turn = slip**2 * (self._turned**2 - before_turn**2)
        noise = _diagonal(grown_distance, grown_distance, grown_turn + grown_distance / 1e6)
        state.covariance = _add(_mul(_mul(jacobian, state.covariance), _t(jacobian)), noise)

    def _predict(self, now: float) -> None:
        state = self._state
        if state is None or now <= state.time:
            return
        seconds = now - state.time
        state.time = now
        if self._speed or self._turn_rate:
            self._apply_move(state, self._speed * seconds, 0.0, self._turn_rate * seconds)
        else:
            walk = self.wander**2 * seconds
            turn_walk = (self.wander / 1000.0) ** 2 * seconds
            state.covariance = _add(state.covariance, _diagonal(walk, walk, turn_walk))

    # ------------------------------------------------------------------ seeing

    async def update(self) -> Estimate | None:
        """Take a picture, fold in the fix its markers give, and return the estimate.

        The fix is folded in where the robot was when the picture was asked for; any
        motion said while the picture was taken is kept.

        :returns: the estimate now (``None`` until a fix has been had).
        :raises RuntimeError: the tracker has no camera.
        :raises ~j5aio.vision.sizes.UnknownMarkerError: the camera saw a marker that its
            table of sizes lacks: give it the map's,
            ``camera.set_marker_sizes(arena_map.marker_sizes())``.
        """
        if self._camera is None:
            raise RuntimeError(
                "this PositionTracker has no camera: give it robot.camera, or feed it with "
                "observe(markers)"
            )
        taken = self._clock()
        self._predict(taken)
        before = None if self._state is None else _State(
            taken, list(self._state.mean), [list(row) for row in self._state.covariance]
        )
        markers = await self._camera.see()
        self._fold(markers, taken, before)
        return self.estimate()

    def observe(self, markers: Iterable[MarkerLike], at: float | None = None) -> Estimate | None:
        """Fold in the fix of one picture's markers, taken at ``at``; return the estimate.

        ``at`` is the tracker's clock time the picture was taken (now by default). For a
        program that looks through the camera itself (``markers = await
        robot.camera.see()``, or a competition API's camera).
        """
        taken = self._clock() if at is None else at
        self._predict(taken)
        self._fold(markers, taken, None)
        return self._estimate()

    def reset(self, pose: Sequence[float] | None = None, *, position_error: float = 50.0,
              heading_error: float = 0.05) -> None:
        """Forget the estimate; or, given ``(x, y, heading)``, start from that pose.

        :param pose: where the robot is known to be (its starting zone), or ``None``.
        :param position_error: how well ``pose`` is known, mm.
        :param heading_error: how well its heading is known, radians.
        """
        self._speed = self._turn_rate = 0.0
        self._set_aside = []
        self._travelled = self._turned = 0.0
        if pose is None:
            self._state, self._last_fix = None, None
            return
        x, y, heading = (float(v) for v in pose)
        now = self._clock()
        self._last_fix = Location(
            x, y, _wrap(heading), position_error, heading_error, (), (),
            tuple(tuple(row) for row in _diagonal(  # type: ignore[misc]
                position_error**2 / 2, position_error**2 / 2, heading_error**2
            )),
        )
        self._fix_time = now
        self._state = _State(
            now, [x, y, _wrap(heading)],
            _diagonal(position_error**2 / 2, position_error**2 / 2, heading_error**2),
        )

    async def run(self, interval: float = 0.0) -> None:
        """Look through the camera again and again, until cancelled (run it in a task group).

        :param interval: seconds to wait between pictures (0: as fast as the camera goes).
        """
        interval = check_number(
            interval, name="interval", low=0.0, high=3600.0, allowed="seconds, 0 or more"
        )
        while True:
            await self.update()
            await anyio.sleep(interval)

    # ------------------------------------------------------------------ fusing

    def _fold(self, markers: Iterable[MarkerLike], taken: float, before: _State | None) -> None:
        prior = None if self._state is None else self._state.mean
        fix = locate(markers, self._map, self._mount, prior=prior)
        if fix is None:
            return
        state = self._state
        if state is None:
            self._start_from(fix, taken)
            return
        base = before if before is not None else _State(
            state.time, list(state.mean), [list(row) for row in state.covariance]
        )
        fused = self._fuse(base, fix)
        if fused is None:
            self._set_aside.append(fix)
            if len(self._set_aside) >= RESTART_AFTER:
                self._start_from(fix, taken)
            return
        self._set_aside = []
        # Carry the motion said since the picture was asked for onto the fused pose.
        move = _relative(base.mean, state.mean)
        growth = [
            [state.covariance[i][j] - base.covariance[i][j] for j in range(3)] for i in range(3)
        ]
        state.mean = _compose(fused.mean, move)
        state.covariance = _add(fused.covariance, growth)
        self._last_fix, self._fix_time = fix, taken
        self._travelled = self._turned = 0.0

    def _start_from(self, fix: Location, taken: float) -> None:
        now = max(taken, self._state.time if self._state is not None else taken)
        self._state = _State(
            now, [fix.x, fix.y, fix.heading], [list(row) for row in fix.covariance]
        )
        self._last_fix, self._fix_time = fix, taken
        self._travelled = self._turned = 0.0
        self._set_aside = []

    @staticmethod
    def _fuse(state: _State, fix: Location) -> _State | None:
        """The Kalman update of ``state`` by ``fix``; ``None`` if the fix is beyond the gate."""
        p = state.covariance
        r = [list(row) for row in fix.covariance]
        s_inverse = _inverse(_add(p, r))
        if s_inverse is None:  # pragma: no cover - a fix's covariance is positive definite
            return None
        innovation = [
            fix.x - state.mean[0], fix.y - state.mean[1], _wrap(fix.heading - state.mean[2])
        ]
        distance = sum(
            innovation[i] * s_inverse[i][j] * innovation[j] for i in range(3) for j in range(3)
        )
        if distance > GATE:
            return None
        gain = _mul(p, s_inverse)
        step = [sum(gain[i][j] * innovation[j] for j in range(3)) for i in range(3)]
        identity = _diagonal(1.0, 1.0, 1.0)
        keep = [[identity[i][j] - gain[i][j] for j in range(3)] for i in range(3)]
        return _State(
            state.time,
            [state.mean[0] + step[0], state.mean[1] + step[1], _wrap(state.mean[2] + step[2])],
            _mul(keep, p),
        )
