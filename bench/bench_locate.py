"""Locating the robot from its camera's markers: accuracy, robustness, cost, and tracking.

Run:  PYTHONPATH=. python bench/bench_locate.py [--poses 500] [--seed 1] [--arena FILE]
      [--resolution 1280x720] [--rough] [--drive-seconds 60]

Every figure comes from real pictures: the simulated camera renders the arena from the
robot's pose, the real detector finds the markers, and :func:`j5aio.vision.locate.locate`
(or :class:`j5aio.vision.track.PositionTracker`) works out the pose, which is compared
with the simulator's true pose. Four parts:

1. random poses inside the arena, each looking at one wall marker or more: position and
   heading errors, for the pictures with two or more wall markers and those with exactly
   one (and how often ``locate`` answered);
2. the same poses, with one picture in five carrying an extra marker on a wall in view
   whose id is wrong: half the time an id on no wall, half the time the id of a wall
   marker that is elsewhere;
3. what ``locate`` costs a picture, beside what detection costs;
4. a drive of 60 s (simulated time) between random waypoints, with a picture every
   0.2 s and the camera covered for 1-3 s at a time; the tracker is told the speeds the
   program asks for (5 % off the truth, as real speeds are), and its estimate is
   compared with the truth 20 times a second.

``--arena FILE`` uses a TOML or JSON arena description (as
:meth:`j5aio.vision.arena_map.ArenaMap.load` reads) instead of the standard arena; the
arena then has no tokens. Needs the vision extra. The default run (500 poses, the goals'
number) takes under a minute on a two-core machine.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import random
import statistics
import time
from collections.abc import Sequence
from pathlib import Path

from j5aio.simulator.arena import Arena, ArenaMarker, Pose, SimulatedWorld
from j5aio.simulator.camera import SimulatedCamera, render_view, visible_markers
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.detect import MarkerDetector
from j5aio.vision.locate import locate
from j5aio.vision.markers import Marker
from j5aio.vision.render import Lighting
from j5aio.vision.track import PositionTracker

GOALS = {
    "two or more: position median": 30.0,
    "two or more: position p95": 80.0,
    "two or more: heading median": 1.0,
    "two or more: heading p95": 3.0,
    "exactly one: position median": 60.0,
    "exactly one: heading median": 2.0,
}


#: The camera of the run (``--rough`` changes its lighting).
CAMERA = [SimulatedCamera()]


def percentile(values: Sequence[float], fraction: float) -> float:
    """The ``fraction`` percentile (nearest rank) of ``values``; NaN when there are none."""
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, math.ceil(fraction * len(ordered)) - 1))]


def arena_from_map(arena_map: ArenaMap) -> Arena:
    """A simulated arena with the map's wall markers (and no tokens)."""
    markers = tuple(
        ArenaMarker(m.id, m.size, m.x, m.y, m.z, m.facing) for m in arena_map.markers
    )
    return Arena(arena_map.width, arena_map.length, 500.0, markers, ())


def random_pose(rng: random.Random, arena: Arena, margin: float) -> Pose:
    """A pose anywhere in the arena, at least ``margin`` mm from the walls."""
    return Pose(
        rng.uniform(margin, arena.width - margin),
        rng.uniform(margin, arena.length - margin),
        rng.uniform(-math.pi, math.pi),
    )


def wall_ids_in_view(world: SimulatedWorld, camera: SimulatedCamera) -> set[int]:
    """The ids of the wall markers the camera has in view (the truth)."""
    wall = {m.marker_id for m in world.arena.markers}
    return {m.marker_id for m in visible_markers(world, camera)} & wall


def wrong_marker(
    rng: random.Random, world: SimulatedWorld, camera: SimulatedCamera, arena_map: ArenaMap
) -> ArenaMarker | None:
    """A marker with a wrong id, on a wall in the camera's view, clear of the real markers."""
    arena = world.arena
    wall_ids = [m.id for m in arena_map.markers]
    used = set(wall_ids) | set(arena_map.token_ids)
    strays = [i for i in range(587) if i not in used]
    size = arena.markers[0].size if arena.markers else 150.0
    height = arena.markers[0].z if arena.markers else 250.0
    walls = (
        (lambda t: (t * arena.width, 0.0), math.pi / 2),
        (lambda t: (arena.width, t * arena.length), math.pi),
        (lambda t: (t * arena.width, arena.length), -math.pi / 2),
        (lambda t: (0.0, t * arena.length), 0.0),
    )
    marker_id = rng.choice(strays) if rng.random() < 0.5 else rng.choice(wall_ids)
    for _ in range(40):
        place, facing = rng.choice(walls)
        x, y = place(rng.uniform(0.05, 0.95))
        if any(math.hypot(m.x - x, m.y - y) < 1.5 * size for m in arena.markers):
            continue
        if marker_id in wall_ids:
            real = arena_map.wall_marker(marker_id)
            assert real is not None
            if math.hypot(real.x - x, real.y - y) < 500:
                continue  # not much of a wrong place
        fake = ArenaMarker(marker_id, size, x, y, height, facing)
        trial = dataclasses.replace(
            world, arena=dataclasses.replace(arena, markers=(*arena.markers, fake))
        )
        if any(
            m.marker_id == marker_id and abs(m.position.distance - math.dist(
                trial.camera_position()[:2], (x, y)
            )) < 300
            for m in visible_markers(trial, camera)
        ):
            return fake
    return None


@dataclasses.dataclass
class Tally:
    """Errors of the located poses, by how many wall markers were detected."""

    many_position: list[float] = dataclasses.field(default_factory=list)
    many_heading: list[float] = dataclasses.field(default_factory=list)
    one_position: list[float] = dataclasses.field(default_factory=list)
    one_heading: list[float] = dataclasses.field(default_factory=list)
    many_frames: int = 0
    one_frames: int = 0
    within_claim: int = 0
    located: int = 0
    wrong_shown: int = 0
    wrong_detected: int = 0
    wrong_used: int = 0
    wrong_unanswered: int = 0
    worst: list[tuple[float, str]] = dataclasses.field(default_factory=list)

    def report(self, title: str) -> None:
        """Print the figures against the goals."""
        print(f"\n{title}")
        figures = {
            "two or more: position median": percentile(self.many_position, 0.5),
            "two or more: position p95": percentile(self.many_position, 0.95),
            "two or more: heading median": percentile(self.many_heading, 0.5),
            "two or more: heading p95": percentile(self.many_heading, 0.95),
            "exactly one: position median": percentile(self.one_position, 0.5),
            "exactly one: heading median": percentile(self.one_heading, 0.5),
        }
        for name, value in figures.items():
            unit = "mm" if "position" in name else "°"
            goal = GOALS[name]
            verdict = "ok" if value <= goal else "MISSED"
            print(f"  {name:32s} {value:8.2f} {unit:2s} (goal <= {goal:g}) {verdict}")
        print(
            f"  located {len(self.many_position)}/{self.many_frames} pictures with two or more "
            f"wall markers detected, {len(self.one_position)}/{self.one_frames} with one; "
            f"p99 position error {percentile(self.many_position + self.one_position, 0.99):.0f} mm"
        )
        if self.located:
            print(
                f"  the true position was within 3x the stated position_error in "
                f"{100 * self.within_claim / self.located:.0f} % of answers"
            )
        if self.wrong_shown:
            print(
                f"  wrong markers: {self.wrong_shown} put in view, {self.wrong_detected} "
                f"detected, {self.wrong_used} used by locate; {self.wrong_unanswered} pictures "
                "with one left unanswered (no majority)"
            )
        for error, what in sorted(self.worst, reverse=True)[:3]:
            print(f"  worst: {error:.0f} mm  {what}")


def still_poses(
    arena: Arena,
    arena_map: ArenaMap,
    poses: int,
    seed: int,
    wrong_every: int,
    detector: MarkerDetector,
    timings: dict[str, list[float]],
) -> Tally:
    """Parts 1 and 2: locate from pictures at random poses."""
    rng = random.Random(seed)
    camera = CAMERA[0]
    calibration, _ = camera.model()
    world = SimulatedWorld(arena=arena)
    mount = world.camera_mount()
    tally = Tally()
    done = 0
    while done < poses:
        pose = random_pose(rng, arena, world.drive.radius + 50)
        world.place_robot(pose)
        if not wall_ids_in_view(world, camera):
            continue
        done += 1
        shown = world
        fake = None
        if wrong_every and done % wrong_every == 0:
            fake = wrong_marker(rng, world, camera, arena_map)
            if fake is not None:
                shown = dataclasses.replace(
                    world, arena=dataclasses.replace(arena, markers=(*arena.markers, fake))
                )
        picture = render_view(shown, camera)
        sizes = shown.arena.marker_sizes()
        started = time.perf_counter()
        markers = detector.detect(picture, calibration, sizes)
        detected = time.perf_counter()
        where = locate(markers, arena_map, mount)
        located = time.perf_counter()
        timings["detect"].append(detected - started)
        timings["locate"].append(located - detected)
        real_walls = [
            m for m in markers if arena_map.wall_marker(m.id) is not None
            and (fake is None or m.id != fake.marker_id or _is_real(m, world, arena_map))
        ]
        if fake is not None:
            tally.wrong_shown += 1
            fakes = [m for m in markers if m.id == fake.marker_id and not _is_real(
                m, world, arena_map)]
            tally.wrong_detected += bool(fakes)
            if where is not None and fakes and fake.marker_id in where.used and not any(
                m.id == fake.marker_id and _is_real(m, world, arena_map) for m in markers
            ):
                tally.wrong_used += 1
            if fakes and where is None:
                tally.wrong_unanswered += 1
        many = len(real_walls) >= 2
        if many:
            tally.many_frames += 1
        elif len(real_walls) == 1:
            tally.one_frames += 1
        else:
            continue
        if where is None:
            continue
        error = math.hypot(where.x - pose.x, where.y - pose.y)
        heading = abs(math.degrees(math.remainder(where.heading - pose.heading, math.tau)))
        (tally.many_position if many else tally.one_position).append(error)
        (tally.many_heading if many else tally.one_heading).append(heading)
        tally.located += 1
        tally.within_claim += error <= 3 * where.position_error
        tally.worst.append(
            (error, f"pose {pose}, used {where.used}, rejected {where.rejected}, fake {fake}")
        )
    return tally


def _is_real(marker: Marker, world: SimulatedWorld, arena_map: ArenaMap) -> bool:
    """Whether a detected marker is the real wall marker of its id (not a fake copy)."""
    wall = arena_map.wall_marker(marker.id)
    if wall is None:
        return False
    cx, cy, _ = world.camera_position()
    horizontal = math.hypot(wall.x - cx, wall.y - cy)
    return abs(marker.position.distance - horizontal) < 0.15 * horizontal + 100


def drive(arena: Arena, arena_map: ArenaMap, seconds: float, seed: int,
          detector: MarkerDetector) -> None:
    """Part 4: track through a drive with the camera covered now and then."""
    rng = random.Random(seed)
    camera = CAMERA[0]
    calibration, _ = camera.model()
    world = SimulatedWorld(arena=arena)
    world.place_robot(Pose(arena.width / 2, arena.length / 4, math.pi / 2))
    clock = [0.0]
    tracker = PositionTracker(None, arena_map, world.camera_mount(), clock=lambda: clock[0])
    sizes = arena.marker_sizes()
    # The program's belief about its speeds: 5 % and 3 % off the simulator's.
    believed_speed = world.drive.max_speed * 0.95
    believed_track = world.drive.track_width * 1.03
    margin = 900.0
    waypoint = (
        rng.uniform(margin, arena.width - margin), rng.uniform(margin, arena.length - margin)
    )
    step = 0.05
    frame_every = 4  # steps: a picture every 0.2 s
    blind_until = 0.0
    next_blind = rng.uniform(2.0, 5.0)
    errors: list[float] = []
    blind_errors: list[float] = []
    stale: list[float] = []
    world.update(0.0, 0.0, 0.0)
    steps = int(seconds / step)
    for k in range(steps + 1):
        now = k * step
        clock[0] = now
        pose = world.update(now, *_steer(world.pose, waypoint))
        if math.hypot(waypoint[0] - pose.x, waypoint[1] - pose.y) < 150:
            waypoint = (
                rng.uniform(margin, arena.width - margin),
                rng.uniform(margin, arena.length - margin),
            )
        left, right = _steer(pose, waypoint)
        world.update(now, left, right)
        tracker.set_motion(
            (left + right) / 2 * believed_speed, (right - left) * believed_speed / believed_track
        )
        if now >= next_blind:
            blind_until = now + rng.uniform(1.0, 3.0)
            next_blind = blind_until + rng.uniform(2.0, 5.0)
        covered = now < blind_until
        if k % frame_every == 0 and not covered:
            markers = detector.detect(render_view(world, camera), calibration, sizes)
            tracker.observe(markers, at=now)
        estimate = tracker.estimate()
        if estimate is None or now < 1.0:
            continue
        error = math.hypot(estimate.x - pose.x, estimate.y - pose.y)
        errors.append(error)
        if covered:
            blind_errors.append(error)
        stale.append(estimate.age)
    print(f"\n4. tracking through a {seconds:.0f} s drive (camera covered 1-3 s at a time)")
    median = percentile(errors, 0.5)
    verdict = "ok" if median <= 100 else "MISSED"
    print(f"  position error median {median:7.1f} mm (goal <= 100) {verdict}")
    print(f"  position error p95    {percentile(errors, 0.95):7.1f} mm")
    print(
        f"  while covered: median {percentile(blind_errors, 0.5):.1f} mm, "
        f"p95 {percentile(blind_errors, 0.95):.1f} mm, max {max(blind_errors, default=0):.1f} mm"
    )
    print(f"  estimate age: median {percentile(stale, 0.5):.2f} s, max {max(stale):.2f} s")


def _steer(pose: Pose, waypoint: tuple[float, float]) -> tuple[float, float]:
    """Wheel powers that turn towards the waypoint and drive on when facing it."""
    bearing = math.atan2(waypoint[1] - pose.y, waypoint[0] - pose.x)
    error = math.remainder(bearing - pose.heading, math.tau)
    turn = max(-0.3, min(0.3, 0.8 * error))
    forward = 0.45 if abs(error) < math.radians(30) else 0.0
    return forward - turn, forward + turn


def main() -> None:
    """Run the four parts and print their figures."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=500, help="random poses")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--arena", type=Path, help="a TOML or JSON arena description")
    parser.add_argument("--drive-seconds", type=float, default=60.0)
    parser.add_argument(
        "--resolution", default="1280x720", help="the camera's pictures, WIDTHxHEIGHT (16:9)"
    )
    parser.add_argument(
        "--rough", action="store_true",
        help="pictures as a real camera's: blurred (0.8 px), noisy (4 levels), darker",
    )
    options = parser.parse_args()
    if options.arena is not None:
        arena_map = ArenaMap.load(options.arena)
        arena = arena_from_map(arena_map)
    else:
        arena = Arena.standard()
        arena_map = arena.arena_map()
    width, height = (int(v) for v in options.resolution.lower().split("x"))
    lighting = Lighting(brightness=0.8, blur=0.8, noise=4.0) if options.rough else None
    CAMERA[0] = SimulatedCamera(resolution=(width, height), lighting=lighting)
    detector = MarkerDetector()
    timings: dict[str, list[float]] = {"detect": [], "locate": []}
    began = time.perf_counter()
    still_poses(arena, arena_map, options.poses, options.seed, 0, detector, timings).report(
        f"1. {options.poses} random poses, at least one wall marker in view"
    )
    still_poses(
        arena, arena_map, options.poses, options.seed + 1000, 5, detector, timings
    ).report(f"2. {options.poses} random poses, one picture in five with a wrong marker")
    print("\n3. cost per picture (parts 1 and 2)")
    for name in ("detect", "locate"):
        values = timings[name]
        print(
            f"  {name:7s} median {1000 * statistics.median(values):7.3f} ms, "
            f"p95 {1000 * percentile(values, 0.95):7.3f} ms"
        )
    verdict = "ok" if statistics.median(timings["locate"]) <= 0.001 else "MISSED"
    print(f"  locate adds <= 1 ms a picture (median): {verdict}")
    drive(arena, arena_map, options.drive_seconds, options.seed, detector)
    print(f"\n(ran in {time.perf_counter() - began:.0f} s)")


if __name__ == "__main__":
    main()
