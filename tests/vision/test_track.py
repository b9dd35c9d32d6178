"""PositionTracker: an estimate carried between pictures (synthetic markers, a fake clock)."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import anyio
import anyio.lowlevel
import pytest

from j5aio.components.marker_camera import MarkerCamera, MarkerCameraInterface
from j5aio.simulator.arena import Pose, SimulatedWorld
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.calibration import CameraCalibration
from j5aio.vision.image import Image
from j5aio.vision.markers import Marker
from j5aio.vision.sizes import MarkerSizes
from j5aio.vision.track import GATE, RESTART_AFTER, Estimate, PositionTracker

from .markers_from_truth import true_markers

ARENA = ArenaMap.standard()


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


class ScriptedCamera(MarkerCameraInterface):
    """A camera backend that reports the markers of a world, then runs ``during``."""

    def __init__(self, world: SimulatedWorld) -> None:
        self.world = world
        self.pictures = 0
        self.during: Callable[[], None] | None = None

    async def see_markers(self, identifier: int, marker_sizes: MarkerSizes) -> list[Marker]:
        self.pictures += 1
        markers = true_markers(self.world)
        if self.during is not None:
            self.during()
        await anyio.lowlevel.checkpoint()
        return markers

    async def see_marker_ids(self, identifier: int) -> list[int]:
        raise NotImplementedError

    async def capture_frame(self, identifier: int) -> Image:
        raise NotImplementedError

    async def save_annotated_frame(
        self, identifier: int, path: Path, marker_sizes: MarkerSizes
    ) -> None:
        raise NotImplementedError

    async def get_calibration(self, identifier: int) -> CameraCalibration | None:
        raise NotImplementedError


def world_at(pose: Pose) -> SimulatedWorld:
    world = SimulatedWorld()
    world.place_robot(pose)
    return world


def close_to(
    estimate: Estimate | None, x: float, y: float, heading: float, mm: float = 1.0
) -> Estimate:
    assert estimate is not None
    assert math.hypot(estimate.x - x, estimate.y - y) < mm
    assert abs(math.remainder(estimate.heading - heading, math.tau)) < 1e-3
    return estimate


def test_a_fix_is_carried_on_by_the_speed_the_program_says() -> None:
    clock = Clock()
    world = world_at(Pose(2000.0, 2000.0, 0.0))
    tracker = PositionTracker(None, ARENA, world.camera_mount(), clock=clock)
    assert tracker.estimate() is None
    assert tracker.observe([]) is None
    first = close_to(tracker.observe(true_markers(world)), 2000.0, 2000.0, 0.0)
    assert first.age == 0.0 and first.last_fix.used
    tracker.set_motion(speed=200.0)
    clock.now += 2.0
    later = close_to(tracker.estimate(), 2400.0, 2000.0, 0.0)
    assert later.age == pytest.approx(2.0)
    assert later.position_error > first.position_error
    tracker.set_motion(0.0, turn_rate=math.pi / 4)
    clock.now += 2.0
    close_to(tracker.estimate(), 2400.0, 2000.0, math.pi / 2)
    assert tracker.arena_map is ARENA and tracker.mount == world.camera_mount()


def test_moves_said_by_the_program_follow_arcs() -> None:
    clock = Clock()
    tracker = PositionTracker(None, ARENA, clock=clock)
    tracker.reset((1000.0, 1000.0, 0.0), position_error=10.0)
    tracker.moved(500.0 * math.pi / 2, math.pi / 2)  # a quarter circle of radius 500 mm
    close_to(tracker.estimate(), 1500.0, 1500.0, math.pi / 2)
    tracker.moved(0.0, left=100.0)
    close_to(tracker.estimate(), 1400.0, 1500.0, math.pi / 2)
    before = tracker.estimate()
    assert before is not None and before.position_error > 10.0
    tracker.reset()
    assert tracker.estimate() is None
    tracker.moved(100.0)  # nothing to move: no error
    assert tracker.estimate() is None


def test_without_motion_the_uncertainty_grows_by_the_wander() -> None:
    clock = Clock()
    tracker = PositionTracker(None, ARENA, wander=100.0, clock=clock)
    tracker.reset((1000.0, 1000.0, 0.0), position_error=0.0, heading_error=0.0)
    clock.now += 4.0
    estimate = close_to(tracker.estimate(), 1000.0, 1000.0, 0.0)
    # a random walk of 100 mm/s: sigma 100 mm a second in x and in y, over 4 s
    assert estimate.position_error == pytest.approx(math.sqrt(2 * 4) * 100.0)
    assert estimate.age == pytest.approx(4.0)


def test_a_new_fix_is_weighed_with_the_estimate() -> None:
    clock = Clock()
    world = world_at(Pose(2000.0, 2000.0, 0.0))
    tracker = PositionTracker(None, ARENA, world.camera_mount(), clock=clock)
    tracker.reset((1990.0, 2000.0, 0.0), position_error=20.0, heading_error=0.01)
    fused = tracker.observe(true_markers(world))
    assert fused is not None
    # between the two, much nearer the fix (which is far more certain)
    assert 1995.0 < fused.x <= 2000.5
    assert fused.age == 0.0


def test_fixes_far_from_the_estimate_are_set_aside_then_believed() -> None:
    clock = Clock()
    world = world_at(Pose(2000.0, 2000.0, 0.0))
    tracker = PositionTracker(None, ARENA, world.camera_mount(), wander=0.0, clock=clock)
    tracker.reset((3000.0, 3000.0, 0.0), position_error=10.0, heading_error=0.01)
    markers = true_markers(world)
    for _ in range(RESTART_AFTER - 1):
        kept = tracker.observe(markers)
        close_to(kept, 3000.0, 3000.0, 0.0)
    # The robot was moved: after so many fixes in a row, the estimate starts again.
    close_to(tracker.observe(markers), 2000.0, 2000.0, 0.0)
    assert GATE > 3


async def test_update_looks_through_the_camera_and_keeps_motion_said_meanwhile() -> None:
    clock = Clock()
    world = world_at(Pose(2000.0, 2000.0, math.pi / 2))
    backend = ScriptedCamera(world)
    camera = MarkerCamera(0, backend)
    tracker = PositionTracker(camera, ARENA, world.camera_mount(), clock=clock)
    close_to(await tracker.update(), 2000.0, 2000.0, math.pi / 2)
    tracker.reset((1990.0, 2000.0, math.pi / 2))

    def drive_on() -> None:  # the program moves while the picture is taken
        clock.now += 0.5
        tracker.moved(100.0)

    backend.during = drive_on
    close_to(await tracker.update(), 2000.0, 2100.0, math.pi / 2, mm=2.0)
    assert backend.pictures == 2


async def test_run_keeps_looking_until_cancelled() -> None:
    world = world_at(Pose(2000.0, 2000.0, 0.0))
    backend = ScriptedCamera(world)
    tracker = PositionTracker(MarkerCamera(0, backend), ARENA, world.camera_mount())
    with anyio.move_on_after(5):
        async with anyio.create_task_group() as group:
            group.start_soon(tracker.run)
            while backend.pictures < 3:
                await anyio.lowlevel.checkpoint()
            group.cancel_scope.cancel()
    assert backend.pictures >= 3
    close_to(tracker.estimate(), 2000.0, 2000.0, 0.0, mm=5.0)


async def test_bad_arguments_say_what_is_allowed() -> None:
    tracker = PositionTracker(None, ARENA)
    with pytest.raises(RuntimeError, match="has no camera"):
        await tracker.update()
    with pytest.raises(TypeError, match="camera must be a MarkerCamera"):
        PositionTracker("camera", ARENA)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="arena_map must be an ArenaMap"):
        PositionTracker(None, "arena")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="wander must be a speed"):
        PositionTracker(None, ARENA, wander=-1.0)
    with pytest.raises(ValueError, match="speed must be"):
        tracker.set_motion(math.inf)
    with pytest.raises(TypeError, match="forward must be"):
        tracker.moved("far")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="interval must be seconds"):
        await tracker.run(-1.0)


def test_an_estimate_reads_well() -> None:
    tracker = PositionTracker(None, ARENA, clock=Clock())
    tracker.reset((1000.0, 2000.0, 0.0), position_error=30.0, heading_error=math.radians(2))
    assert str(tracker.estimate()) == (
        "(1000, 2000) mm ± 30, heading 0.0° ± 2.0°, 0.0 s since markers were seen"
    )


def test_a_singular_matrix_has_no_inverse() -> None:
    from j5aio.vision.track import _inverse

    assert _inverse([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]) is None
    assert _inverse([[2.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 0.5]]) == [
        [0.5, 0.0, 0.0], [0.0, 0.25, 0.0], [0.0, 0.0, 2.0]
    ]


def test_the_uncertainty_of_a_move_does_not_depend_on_how_it_was_said() -> None:
    def after(pieces: int) -> float:
        tracker = PositionTracker(None, ARENA, slip=0.1, clock=Clock())
        tracker.reset((1000.0, 1000.0, 0.0), position_error=0.0, heading_error=0.0)
        for _ in range(pieces):
            tracker.moved(1000.0 / pieces)
        estimate = close_to(tracker.estimate(), 2000.0, 1000.0, 0.0)
        return estimate.position_error

    # a tenth of the 1000 mm driven, in x and in y
    assert after(1) == pytest.approx(math.sqrt(2) * 100.0)
    # In pieces, the heading's growing uncertainty also spreads the later pieces a little;
    # the growth does not add up piece by piece (10 pieces of 100 mm would give a third).
    assert after(10) == pytest.approx(after(1), rel=0.05)
    assert after(100) == pytest.approx(after(10), rel=0.05)
