"""The simulated arena and drive model (pure geometry: no optional libraries needed)."""

from __future__ import annotations

import math

import pytest

from j5aio.simulator.arena import Arena, DifferentialDrive, Pose, SimulatedWorld, Token


def test_the_standard_arena_has_seven_markers_a_wall_facing_inwards() -> None:
    arena = Arena.standard()
    assert [m.marker_id for m in arena.markers] == list(range(28))
    for marker in arena.markers:
        # one step along its facing goes further into the arena
        x = marker.x + 10 * math.cos(marker.facing)
        y = marker.y + 10 * math.sin(marker.facing)
        assert 0 < x < arena.width and 0 < y < arena.length
    sizes = arena.marker_sizes()
    assert sizes.size_of(0) == 150 and sizes.size_of(100) == 80
    assert len(list(arena.all_markers())) == 28 + 4 * 4


def test_a_token_has_a_marker_on_each_side() -> None:
    token = Token(100, 1000.0, 2000.0, side=100.0)
    markers = token.markers()
    assert [round(m.facing, 6) for m in markers] == [
        round(k * math.pi / 2, 6) for k in range(4)
    ]
    assert markers[0].x == pytest.approx(1050.0) and markers[0].y == pytest.approx(2000.0)
    assert all(m.z == 50.0 for m in markers)


def test_differential_drive_goes_straight_spins_and_arcs() -> None:
    drive = DifferentialDrive(max_speed=1000.0, track_width=300.0)
    start = Pose(0.0, 0.0, 0.0)
    straight = drive.move(start, 0.5, 0.5, 2.0)
    assert (straight.x, straight.y, straight.heading) == pytest.approx((1000.0, 0.0, 0.0))
    spun = drive.move(start, -0.5, 0.5, 1.0)  # 1000 mm/s difference over 300 mm
    assert (spun.x, spun.y) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert spun.heading == pytest.approx(math.remainder(1000 / 300, math.tau))
    # an arc: a quarter circle of radius r = v / w
    quarter = drive.move(start, 0.25, 0.75, (math.pi / 2) / (500 / 300))
    radius = 500 / (500 / 300)
    assert (quarter.x, quarter.y) == pytest.approx((radius, radius))
    assert quarter.heading == pytest.approx(math.pi / 2)
    # powers beyond full are held at full
    assert drive.move(start, 2.0, 2.0, 1.0).x == pytest.approx(1000.0)


def test_drive_settings_are_checked() -> None:
    with pytest.raises(ValueError, match="max_speed"):
        DifferentialDrive(max_speed=0)
    with pytest.raises(ValueError, match="track_width"):
        DifferentialDrive(track_width=math.nan)


def test_the_world_applies_the_powers_held_since_the_last_update() -> None:
    world = SimulatedWorld(pose=Pose(1000.0, 1000.0, 0.0))
    world.update(10.0, 1.0, 1.0)  # the first update only starts the clock
    assert world.pose.x == 1000.0
    world.update(10.5, 0.0, 0.0)  # half a second at full power
    assert world.pose.x == pytest.approx(1500.0)
    world.update(11.5, 0.0, 0.0)
    assert world.pose.x == pytest.approx(1500.0)
    world.update(11.0, 1.0, 1.0)  # time never runs backwards
    world.update(11.6, 0.0, 0.0)
    assert world.pose.x == pytest.approx(1600.0)


def test_the_robot_stops_at_the_walls() -> None:
    world = SimulatedWorld(pose=Pose(1000.0, 1000.0, math.pi))
    world.update(0.0, 1.0, 1.0)
    world.update(5.0, 0.0, 0.0)
    assert world.pose.x == pytest.approx(world.drive.radius)
    world.place_robot(Pose(-50.0, 99999.0, 0.0))
    assert (world.pose.x, world.pose.y) == (200.0, world.arena.length - 200.0)


def test_the_camera_sits_on_the_robot() -> None:
    assert SimulatedWorld().camera_forward == SimulatedWorld().drive.radius  # at the front
    world = SimulatedWorld(pose=Pose(1000.0, 500.0, math.pi / 2), camera_forward=100.0)
    assert world.camera_position() == pytest.approx((1000.0, 600.0, world.camera_height))
