"""What the live view shows of the simulated arena and the robot's pose."""

from __future__ import annotations

import math

import pytest

from j5aio.kit import KitRobot
from j5aio.simulator.arena import Arena, ArenaMarker, Pose, SimulatedWorld, Token
from j5aio.simulator.camera import SimulatedCamera
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit
from j5aio.view.arena import describe_arena, describe_pose, field_of_view, kit_of
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.calibration import CameraCalibration
from j5aio.vision.track import PositionTracker

pytestmark = pytest.mark.usefixtures("fresh_kit")


def small_kit() -> SimulatedKit:
    kit = SimulatedKit(KitConfig(1, 1, 0, 0, 0))
    kit.world = SimulatedWorld(
        arena=Arena(
            2000.0,
            3000.0,
            markers=(ArenaMarker(7, 150.0, 1000.0, 0.0, 250.0, math.pi / 2),),
            tokens=(Token(100, 500.0, 600.0, heading=0.25),),
        ),
        pose=Pose(1000.0, 1500.0, math.pi / 2),
    )
    return kit


def test_the_arena_as_the_page_draws_it() -> None:
    kit = small_kit()
    shown = describe_arena(kit)
    assert shown["key"] == kit.name
    assert (shown["width"], shown["length"]) == (2000.0, 3000.0)
    assert shown["markers"] == [
        {"id": 7, "x": 1000.0, "y": 0.0, "size": 150.0, "facing": math.pi / 2}
    ]
    assert shown["tokens"] == [{"id": 100, "x": 500.0, "y": 600.0, "side": 130.0, "heading": 0.25}]
    assert shown["robot"] == {"radius": 200.0, "track_width": 300.0}


def test_the_standard_arena_has_every_wall_marker_and_token() -> None:
    shown = describe_arena(SimulatedKit())
    assert sorted(m["id"] for m in shown["markers"]) == list(range(28))
    assert [t["id"] for t in shown["tokens"]] == [100, 101, 102, 103]


def test_the_field_of_view_follows_the_pinhole_model() -> None:
    left, right = field_of_view(SimulatedCamera())
    # The default camera: 1280 px wide, f = 1387.5 px, centred: about 49.5 degrees across.
    half = math.atan(640 / 1387.5)
    assert left == pytest.approx(half) and right == pytest.approx(-half)
    # A principal point off the middle makes one side wider; a smaller picture is the
    # same camera, so the same angles.
    off = SimulatedCamera(CameraCalibration(1000.0, 1000.0, 299.5, 240.0, (), (800, 480)))
    left, right = field_of_view(off)
    assert left == pytest.approx(math.atan(300 / 1000)) and right == pytest.approx(-math.atan(0.5))
    scaled = field_of_view(SimulatedCamera(resolution=(640, 360)))
    assert scaled == pytest.approx((half, -half), abs=1e-3)


def test_the_pose_and_what_the_camera_sees() -> None:
    kit = small_kit()
    shown = describe_pose(kit)
    assert (shown["x"], shown["y"], shown["heading"]) == (1000.0, 1500.0, math.pi / 2)
    camera = shown["camera"]
    # The camera is at the robot's front (200 mm ahead), looking where the robot heads.
    assert camera["x"] == pytest.approx(1000.0) and camera["y"] == pytest.approx(1700.0)
    half = math.atan(640 / 1387.5)
    assert camera["left"] == pytest.approx(math.pi / 2 + half)
    assert camera["right"] == pytest.approx(math.pi / 2 - half)
    kit.camera = None
    assert describe_pose(kit)["camera"] is None


def test_the_estimate_of_a_tracker_is_shown_beside_the_true_pose() -> None:
    kit = small_kit()
    assert describe_pose(kit)["estimate"] is None
    tracker = PositionTracker(None, ArenaMap.standard(), clock=lambda: 10.0)
    tracker.reset((900.0, 1450.0, 1.5), position_error=40.0)
    assert tracker.estimate() is not None
    shown = describe_pose(kit)["estimate"]
    assert shown == {"x": 900.0, "y": 1450.0, "heading": 1.5, "error": pytest.approx(40.0),
                     "age": 0.0}
    del tracker  # gone with its tracker
    assert describe_pose(kit)["estimate"] is None


def test_the_pose_moves_as_the_world_does() -> None:
    kit = small_kit()
    kit.world.update(0.0, 0.5, 0.5)
    kit.world.update(1.0, 0.5, 0.5)  # 1 s at half of 1 m/s, northwards
    assert describe_pose(kit)["y"] == pytest.approx(2000.0)
    assert describe_pose(kit)["x"] == pytest.approx(1000.0)


async def test_the_kit_of_the_boards() -> None:
    kit = use_kit(KitConfig(1, 1, 0, 0, 0))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert kit_of(robot.boards()) is kit  # the camera knows its kit
        assert kit_of([robot.power_board]) is kit  # any simulated board: the current kit
        assert kit_of([]) is None


async def test_hardware_boards_have_no_arena() -> None:
    import contextlib
    import io

    from j5aio.environments import console_environment

    with contextlib.redirect_stdout(io.StringIO()):
        async with KitRobot(environment=console_environment()) as robot:
            assert kit_of([robot.power_board, *robot.motor_boards]) is None
