"""locate(): the robot's pose from one picture's markers (synthetic markers: no picture)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import pytest

from j5aio.simulator.arena import Pose, SimulatedWorld
from j5aio.vision.arena_map import ArenaMap, WallMarker
from j5aio.vision.locate import CameraMount, Location, RejectedMarker, locate, marker_position
from j5aio.vision.markers import Marker, Orientation, PixelCoordinates, Position

from .markers_from_truth import true_markers

ARENA = ArenaMap.standard()


def heading_error(a: float, b: float) -> float:
    return abs(math.remainder(a - b, math.tau))


def walls(markers: list[Marker]) -> list[Marker]:
    return [m for m in markers if ARENA.wall_marker(m.id) is not None]


def check(where: Location | None, pose: Pose, *, mm: float = 1.0, rad: float = 1e-4) -> Location:
    assert where is not None
    assert math.hypot(where.x - pose.x, where.y - pose.y) < mm
    assert heading_error(where.heading, pose.heading) < rad
    return where


@pytest.mark.parametrize(
    "pose",
    [Pose(2875.0, 1000.0, math.pi / 2), Pose(1000.0, 1500.0, 0.3), Pose(4500.0, 4200.0, -2.5)],
)
def test_many_markers_place_the_robots_centre(pose: Pose) -> None:
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = true_markers(world)
    assert len(walls(markers)) >= 2
    where = check(locate(markers, ARENA, world.camera_mount()), pose)
    assert sorted(where.used) == sorted(m.id for m in walls(markers))
    assert {r.reason for r in where.rejected} <= {"a token"}
    assert 0 < where.position_error < 50
    assert 0 < where.heading_error < math.radians(1)
    assert len(where.covariance) == 3


def test_the_camera_mount_is_allowed_for() -> None:
    pose = Pose(1500.0, 2000.0, 0.7)
    world = SimulatedWorld(camera_forward=120.0, camera_left=80.0, camera_angle=0.4)
    world.place_robot(pose)
    markers = true_markers(world)
    check(locate(markers, ARENA, world.camera_mount()), pose)
    # Taken as a camera at the centre, looking forwards, the answer is the camera's pose.
    where = locate(markers, ARENA)
    assert where is not None
    camera_x, camera_y, _ = world.camera_position()
    assert math.hypot(where.x - camera_x, where.y - camera_y) < 1.0
    assert heading_error(where.heading, pose.heading + 0.4) < 1e-4


def test_a_tilted_camera_is_allowed_for() -> None:
    pose = Pose(1500.0, 2000.0, 0.7)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = true_markers(world, tilt=-0.25)
    check(locate(markers, ARENA, CameraMount(forward=200.0, tilt=-0.25)), pose)
    level = locate(markers, ARENA, CameraMount(forward=200.0))
    assert level is not None and math.hypot(level.x - pose.x, level.y - pose.y) > 20


def test_one_marker_is_enough() -> None:
    pose = Pose(2875.0, 4500.0, math.pi / 2)  # a metre from the north wall, facing it
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    near = min(markers, key=lambda m: m.distance)
    where = check(locate([near], ARENA, world.camera_mount()), pose)
    assert where.used == (near.id,)


def test_distances_are_rescaled_when_the_camera_has_another_size() -> None:
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = true_markers(world, sizes=dict.fromkeys(range(28), 100.0))
    check(locate(markers, ARENA, world.camera_mount()), pose)


def test_unknown_ids_tokens_and_markers_without_a_pose_are_left_out() -> None:
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    stray = markers[0]._replace(id=300)
    token = markers[1]._replace(id=101)
    blind = markers[2]._replace(position=Position(math.nan, math.nan, math.nan))
    corner = markers[3].pixel_centre
    tiny = markers[3]._replace(pixel_corners=(corner, corner, corner, corner))
    seen = [stray, token, blind, tiny, *markers[4:]]
    where = check(locate(seen, ARENA, world.camera_mount()), pose)
    assert set(where.rejected) == {
        RejectedMarker(300, "not on the walls"),
        RejectedMarker(101, "a token"),
        RejectedMarker(blind.id, "no pose (the camera has no calibration)"),
        RejectedMarker(tiny.id, "too small in the picture"),
    }
    assert set(where.used) == {m.id for m in markers[4:]}


def test_a_marker_that_disagrees_is_left_out() -> None:
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    assert len(markers) >= 3
    # Marker 3 (on the south wall) read where a marker of the east wall is.
    wrong = markers[1]._replace(id=3)
    where = check(
        locate([markers[0], wrong, *markers[2:]], ARENA, world.camera_mount()), pose
    )
    assert RejectedMarker(3, "disagrees with the others") in where.rejected
    assert 3 not in where.used


def test_two_markers_that_disagree_give_no_answer_unless_a_prior_chooses() -> None:
    pose = Pose(2875.0, 3500.0, math.pi / 2)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    good = markers[0]
    wrong = markers[1]._replace(id=26)  # a west-wall id, seen on the north wall
    mount = world.camera_mount()
    assert locate([good, wrong], ARENA, mount) is None
    where = check(locate([good, wrong], ARENA, mount, prior=(2800.0, 3400.0, 1.5)), pose)
    assert where.used == (good.id,)
    prior = Location(2800.0, 3400.0, 1.5, 100.0, 0.1, ())
    check(locate([wrong, good], ARENA, mount, prior=prior), pose)


def test_a_lone_marker_too_small_to_trust_gives_no_answer() -> None:
    world = SimulatedWorld()
    world.place_robot(Pose(2875.0, 4500.0, math.pi / 2))
    near = min(walls(true_markers(world, pixels=9.0)), key=lambda m: m.distance)
    assert locate([near], ARENA, world.camera_mount()) is None


def test_no_wall_marker_or_an_answer_outside_the_arena_gives_none() -> None:
    assert locate([], ARENA) is None
    world = SimulatedWorld()
    world.place_robot(Pose(2875.0, 4500.0, math.pi / 2))
    markers = walls(true_markers(world))
    # A map that puts the same markers 3 m further north: the robot would be outside.
    moved = ArenaMap(
        tuple(WallMarker(m.id, m.x, m.y + 3000.0, m.facing, m.size, m.z) for m in ARENA.markers),
        width=ARENA.width,
        length=ARENA.length,
    )
    assert locate(markers, moved, world.camera_mount()) is None
    assert locate([markers[0]], moved, world.camera_mount()) is None


def test_bad_arguments_say_what_is_allowed() -> None:
    with pytest.raises(TypeError, match="arena_map must be an ArenaMap"):
        locate([], {"markers": []})  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="the camera's angle must be a number of radians"):
        CameraMount(angle=4.0)
    with pytest.raises(ValueError, match="the camera's tilt"):
        CameraMount(tilt=2.0)
    with pytest.raises(TypeError, match="forward offset"):
        CameraMount(forward="front")  # type: ignore[arg-type]


def test_a_location_reads_well() -> None:
    where = Location(1000.0, 2000.0, math.pi / 2, 12.3, math.radians(0.5), (3, 4))
    assert str(where) == "(1000, 2000) mm ± 12, heading 90.0° ± 0.5°, from markers 3, 4"
    assert "from marker 3" in str(Location(0.0, 0.0, 0.0, 1.0, 0.0, (3,)))


def test_a_marker_seen_from_a_known_pose_is_placed_in_the_arena() -> None:
    pose = Pose(2875.0, 1000.0, math.pi / 2)
    world = SimulatedWorld(camera_left=30.0, camera_angle=0.1)
    world.place_robot(pose)
    markers = true_markers(world)
    where = locate(markers, ARENA, world.camera_mount())
    assert where is not None
    token = next(m for m in markers if m.id == 102)
    camera_x, camera_y, _ = world.camera_position()
    face = min(  # the face of token 102 nearest the camera is the one in view
        (f for t in world.arena.tokens if t.marker_id == 102 for f in t.markers()),
        key=lambda f: math.hypot(f.x - camera_x, f.y - camera_y),
    )
    x, y = marker_position(token, where, world.camera_mount())
    assert math.hypot(x - face.x, y - face.y) < 2.0
    with pytest.raises(ValueError, match="no pose"):
        marker_position(token._replace(position=Position(math.nan, 0.0, 0.0)), where)


@dataclass
class ForeignMarker:
    """A marker of another API's camera, with the fields locate reads, and no corners."""

    id: int
    size: float
    position: Position
    orientation: Orientation
    pixel_corners: Sequence[PixelCoordinates] = ()


def test_markers_of_another_api_without_pixel_corners_are_used() -> None:
    # Without corners the noise model has only its floors.
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = [
        ForeignMarker(m.id, m.size, m.position, m.orientation) for m in walls(true_markers(world))
    ]
    check(locate(markers, ARENA, world.camera_mount()), pose)


def test_singular_systems_are_reported_not_divided_by() -> None:
    from j5aio.vision.locate import _fit, _inverse3, _solve3

    zeros = [[0.0] * 3 for _ in range(3)]
    assert _solve3(zeros, [1.0, 1.0, 1.0]) is None
    assert _inverse3(zeros) is None
    assert _fit((0.0, 0.0, 0.0), [], CameraMount()) is None


def turned(marker: Marker, degrees: float) -> Marker:
    """The marker with its facing (yaw) reported ``degrees`` off, as a mirrored pose is."""
    yaw, pitch, roll = marker.orientation
    return marker._replace(orientation=Orientation(yaw + math.radians(degrees), pitch, roll))


def test_a_marker_whose_facing_alone_is_wrong_still_gives_its_distance_and_bearing() -> None:
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    markers[1] = turned(markers[1], 40.0)
    where = check(locate(markers, ARENA, world.camera_mount()), pose)
    assert markers[1].id in where.used


def test_markers_that_dispute_each_other_alone_are_left_out() -> None:
    pose = Pose(1000.0, 1500.0, 0.3)
    world = SimulatedWorld()
    world.place_robot(pose)
    markers = walls(true_markers(world))
    assert len(markers) >= 4
    # Each of the two agrees with the rest (whose facings are right), not with the other.
    markers[0], markers[1] = turned(markers[0], 50.0), turned(markers[1], -60.0)
    where = check(locate(markers, ARENA, world.camera_mount()), pose)
    assert {r.id for r in where.rejected if r.reason == "disagrees with the others"} == {
        markers[0].id, markers[1].id
    }
