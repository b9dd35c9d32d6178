"""The simulated camera: a robot on the simulated kit sees the arena through the real detector."""

from __future__ import annotations

import math
import time
from pathlib import Path

import anyio
import pytest

np = pytest.importorskip("numpy")
cv2 = pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

from j5aio.kit import KitRobot  # noqa: E402
from j5aio.simulator.arena import Pose  # noqa: E402
from j5aio.simulator.camera import (  # noqa: E402
    DEFAULT_CALIBRATION,
    SimulatedCamera,
    SimulatedCameraBackend,
    render_view,
    update_world,
    visible_markers,
)
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT  # noqa: E402
from j5aio.simulator.kit import KitConfig, use_kit  # noqa: E402
from j5aio.vision.render import Lighting  # noqa: E402


@pytest.mark.parametrize(
    "pose",
    [
        Pose(2875.0, 1000.0, math.pi / 2),
        Pose(1000.0, 1500.0, 0.3),
        Pose(4500.0, 4200.0, -2.5),
        Pose(2875.0, 2875.0, math.pi),
    ],
)
async def test_see_reports_what_is_really_in_view(pose: Pose) -> None:
    kit = use_kit()
    kit.world.place_robot(pose)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is not None
        seen = await robot.camera.see()
        truth = visible_markers(kit.world, kit.camera)  # type: ignore[arg-type]
        assert truth, "every pose here looks at some markers"
        # Tokens hide what is behind them in the picture (not in the list of truths).
        assert {m.id for m in seen} <= {t.marker_id for t in truth}, "no false ids"
        assert len(seen) >= 0.75 * len(truth)
        for marker in seen:
            candidates = [t for t in truth if t.marker_id == marker.id]
            best = min(candidates, key=lambda t: abs(t.position.distance - marker.distance))
            assert marker.distance == pytest.approx(best.position.distance, rel=0.03)
            bearing_error = marker.position.horizontal_angle - best.position.horizontal_angle
            assert abs(math.degrees(bearing_error)) < 1.5
        assert await robot.camera.see_ids() == sorted(m.id for m in seen)


async def test_a_robot_drives_to_a_marker_using_see_and_stops_within_10cm() -> None:
    """Find marker 17 (the middle of the north wall), steer to it, stop 5 cm in front.

    The camera is at the robot's front. Close up the marker no longer fits in the
    picture, so the last 60 cm are driven from the last sighting, as teams do.
    """
    kit = use_kit(KitConfig(motor_boards=1))
    kit.world.place_robot(Pose(1500.0, 2000.0, 0.6))
    target, gap = 17, 50.0
    speed = kit.world.drive.max_speed
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is not None
        left, right = robot.motor_boards[0].motors[0], robot.motor_boards[0].motors[1]
        with anyio.fail_after(60):
            while True:
                markers = [m for m in await robot.camera.see() if m.id == target]
                if not markers:
                    await left.set_power(-0.2)  # turn left on the spot until it is in view
                    await right.set_power(0.2)
                    continue
                marker = markers[0]
                if marker.cartesian.x < 600 and abs(marker.cartesian.y) < 30:
                    break
                steer = max(-0.2, min(0.2, 1.0 * marker.position.horizontal_angle))
                power = 0.5 if marker.cartesian.x > 1200 else 0.15
                await left.set_power(power + steer)
                await right.set_power(power - steer)
            # the last stretch, blind: distance / speed at 0.25 power
            await left.set_power(0.25)
            await right.set_power(0.25)
            await anyio.sleep((marker.cartesian.x - gap) / (0.25 * speed))
            await left.set_power(0)
            await right.set_power(0)
        update_world(kit)
    wall_marker = next(m for m in kit.world.arena.markers if m.marker_id == target)
    camera = kit.world.camera_position()
    assert math.dist(camera[:2], (wall_marker.x, wall_marker.y)) < 100


async def test_a_kit_without_a_camera_has_none_and_the_camera_settings_apply(
    tmp_path: Path,
) -> None:
    kit = use_kit()
    kit.camera = None
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is None
        assert len(robot.cameras) == 0
    kit = use_kit()
    kit.camera = SimulatedCamera(resolution=(640, 360), lighting=Lighting(noise=3.0, blur=0.5))
    with pytest.raises(ValueError, match="aspect ratio"):
        SimulatedCamera(resolution=(640, 480)).model()
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is not None
        frame = await robot.camera.capture()
        assert frame.shape == (360, 640, 3)
        calibration = await robot.camera.get_calibration()
        assert calibration is not None
        assert calibration.fx == pytest.approx(DEFAULT_CALIBRATION.fx / 2)
        assert len(await robot.camera.see()) > 0
        await robot.camera.save(tmp_path / "view.jpg")
        assert cv2.imread(str(tmp_path / "view.jpg")).shape == (360, 640, 3)
        backend = robot.cameras[0].backend
        assert isinstance(backend, SimulatedCameraBackend)
        assert backend.kit is kit
        assert backend.grab().shape == (360, 640, 3)


async def test_the_world_moves_while_the_program_waits_and_stops_after_close() -> None:
    kit = use_kit(KitConfig(motor_boards=1))
    kit.world.place_robot(Pose(2875.0, 1000.0, math.pi / 2))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        start = time.monotonic()
        await robot.motor_boards[0].motors[0].set_power(0.5)
        await robot.motor_boards[0].motors[1].set_power(0.5)
        await anyio.sleep(0.3)
        elapsed = time.monotonic() - start
        moved = kit.world.pose.y - 1000.0
        # The wheels' speed follows the duty the simulated board drives, for about 0.3 s
        # (a loaded machine may run the world's 10 ms ticks late: the lower bound is loose).
        speed = kit.motor_boards[0].motors[0].power * kit.world.drive.max_speed
        assert speed > 0
        assert speed * 0.2 < moved <= speed * elapsed + 1
        for board in robot.cameras:
            await board.close()
    y = kit.world.pose.y
    await anyio.sleep(0.05)
    assert kit.world.pose.y == y


def test_a_marker_turned_away_is_not_drawn() -> None:
    kit = use_kit()
    kit.world.place_robot(Pose(2875.0, 1000.0, -math.pi / 2))  # facing the south wall
    assert kit.camera is not None
    image = render_view(kit.world, kit.camera)
    assert image.shape == (720, 1280, 3)
    kit.world.place_robot(Pose(2875.0, 300.0, math.pi / 2))  # back to the south wall
    truth = {t.marker_id for t in visible_markers(kit.world, kit.camera)}
    assert not truth & set(range(7))  # the south wall's markers face away from the camera


async def test_cameras_of_one_kit_share_one_clock_that_stops_with_the_last() -> None:
    from j5aio.simulator.camera import _WorldClock

    kit = use_kit(KitConfig(motor_boards=1))
    first = await SimulatedCameraBackend.discover()
    second = await SimulatedCameraBackend.discover()
    clock = _WorldClock._clocks[id(kit)]
    assert clock.users == 2
    kit.world.place_robot(Pose(2875.0, 1000.0, math.pi / 2))
    await first[0].close()
    await first[0].close()  # twice is harmless
    assert clock.users == 1 and clock.timer is None  # the robot is still: no ticks
    await second[0].close()
    assert id(kit) not in _WorldClock._clocks
    assert all(not board._listeners for board in kit.drive_motor_boards)  # nor listens
    _WorldClock.leave(kit)  # a kit without a clock: nothing to do


async def test_the_clock_sleeps_while_the_robot_is_still_and_a_motor_command_wakes_it() -> None:
    from j5aio.simulator.camera import _WorldClock

    kit = use_kit(KitConfig(motor_boards=1))
    kit.world.place_robot(Pose(2875.0, 1000.0, math.pi / 2))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        clock = _WorldClock._clocks[id(kit)]
        assert clock.timer is None
        motors = robot.motor_boards[0].motors
        await motors[0].set_power(0.5)
        assert clock.timer is not None  # the command woke it: it ticks while driving
        await motors[1].set_power(0.5)
        await anyio.sleep(0.2)
        assert kit.world.pose.y > 1000.0
        await motors[0].set_power(0)
        await motors[1].set_power(0)
        stopped = kit.world.pose
        await anyio.sleep(0.05)  # the next tick finds the robot still and sleeps
        assert clock.timer is None
        assert kit.world.pose == stopped


async def test_a_picture_shows_the_pose_of_the_moment_it_was_asked_for() -> None:
    # The view is noted on the event loop and drawn on the worker thread: moving the robot
    # in between does not change the picture.
    kit = use_kit()
    kit.world.place_robot(Pose(2875.0, 1000.0, math.pi / 2))
    backend = SimulatedCameraBackend(kit)
    try:
        source = await backend.frame_source()
        assert kit.camera is not None
        expected = render_view(kit.world, kit.camera)
        kit.world.place_robot(Pose(1000.0, 1500.0, 0.3))
        assert np.array_equal(source(), expected)
        assert not np.array_equal(render_view(kit.world, kit.camera), expected)
    finally:
        await backend.close()
