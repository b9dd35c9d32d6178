"""The simulated kit's world and camera are made when first read, and are the same after."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from j5aio.simulator import kit as kit_module
from j5aio.simulator._camera_backend import SimulatedCameraBackend, update_world
from j5aio.simulator.clock import ManualClock
from j5aio.simulator.kit import SimulatedKit, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode, MotorOutput


@pytest.fixture(autouse=True)
def _no_current_kit() -> Iterator[None]:
    saved = kit_module._current
    kit_module._current = None
    yield
    kit_module._current = saved


def test_the_world_is_made_when_first_read_and_kept() -> None:
    from j5aio.simulator.arena import SimulatedWorld

    kit = SimulatedKit()
    assert not kit.has_world
    world = kit.world
    assert isinstance(world, SimulatedWorld)
    assert kit.has_world
    assert kit.world is world
    other = SimulatedWorld()
    kit.world = other
    assert kit.world is other


def test_the_default_camera_is_made_when_first_read_and_can_be_replaced() -> None:
    from j5aio.simulator.camera import SimulatedCamera

    kit = SimulatedKit()
    assert kit.has_camera
    assert kit._camera_if_made() is None  # not made yet
    camera = kit.camera
    assert camera == SimulatedCamera()
    assert kit.camera is camera is kit.default_camera()
    assert kit._camera_if_made() is camera
    kit.camera = None
    assert not kit.has_camera
    assert kit.camera is None
    assert kit.default_camera() is camera  # the one the kit was made with
    wide = SimulatedCamera(resolution=(640, 360))
    kit.camera = wide
    assert kit.has_camera and kit.camera is wide


def test_a_still_robot_makes_no_world_and_a_moving_one_does() -> None:
    kit = SimulatedKit()
    clock = ManualClock()
    kit.use_clock(clock)
    assert update_world(kit) is False
    assert not kit.has_world  # every motor still: nothing to move
    board = kit.motor_boards[0]
    board._motors = [MotorOutput(MotorMode.FORWARD, 50)] * 2  # (both at half power)
    assert update_world(kit) is True
    assert kit.has_world
    start = kit.world.pose
    clock.advance(1.0)
    update_world(kit)
    assert kit.world.pose != start  # it drove from the first power on


def test_a_world_made_by_reading_it_is_moved_on_with_the_motors_still() -> None:
    kit = SimulatedKit()
    pose = kit.world.pose
    assert update_world(kit) is False
    assert kit.world.pose == pose


def test_the_camera_backend_reads_the_camera_and_the_arena_on_first_use() -> None:
    from j5aio.simulator.camera import DEFAULT_CALIBRATION, SimulatedCamera

    kit = use_kit()
    backend = SimulatedCameraBackend(kit)
    assert not kit.has_world
    assert kit._camera_if_made() is None
    sizes = backend.marker_sizes
    assert not kit.has_world  # the table is not read yet
    assert sizes.size_of(0) == 150.0  # a wall marker
    assert sizes[100] == 80.0  # a token's
    assert kit.has_world
    assert dict(sizes) == dict(kit.world.arena.marker_sizes())
    assert backend._calibration == DEFAULT_CALIBRATION
    assert backend._camera is kit.camera
    # A camera set on the kit afterwards is another camera's, not this backend's.
    kit.camera = SimulatedCamera(resolution=(640, 360))
    assert backend._camera is kit.default_camera()
    assert backend._calibration == DEFAULT_CALIBRATION


def test_a_camera_set_before_the_backend_is_made_is_its_camera() -> None:
    from j5aio.simulator.camera import DEFAULT_CALIBRATION, SimulatedCamera

    kit = use_kit()
    kit.camera = SimulatedCamera(resolution=(640, 360))
    backend = SimulatedCameraBackend(kit)
    assert backend._camera is kit.camera
    calibration = backend._calibration
    assert calibration is not None
    assert calibration.fx == pytest.approx(DEFAULT_CALIBRATION.fx / 2)
    kit.camera = None
    with pytest.raises(ValueError, match="has no camera"):
        SimulatedCameraBackend(kit)


async def test_the_marker_camera_keeps_the_arena_table_unread() -> None:
    from j5aio.boards.camera import CameraBoard
    from j5aio.vision.sizes import MarkerSizes

    kit = use_kit()
    boards = await SimulatedCameraBackend.discover()
    try:
        (board,) = boards
        assert isinstance(board, CameraBoard)
        assert not kit.has_world
        table = board.camera.marker_sizes
        assert isinstance(table, MarkerSizes)
        assert len(table) == 28 + 4
        assert (table | MarkerSizes({5: 10})).size_of(5) == 10
        assert "MarkerSizes(" in repr(table)
    finally:
        for board in boards:
            await board.backend.close()


def test_a_named_kit_makes_its_configuration_when_first_read() -> None:
    from j5aio.simulator.kit import KitConfig

    kit = SimulatedKit("sr2019", time_scale=0.5)
    assert kit._config is None
    assert kit.time_scale == 0.5
    assert kit.config == KitConfig(
        power_boards=1, motor_boards=1, servo_boards=1, sb_arduinos=0, ruggeduinos=1,
        time_scale=0.5,
    )
    assert kit.config is kit.config
    assert "KitConfig(" not in repr(kit)  # a named kit shows its name
    from_counts = SimulatedKit(KitConfig(motor_boards=1))
    assert "KitConfig(" in repr(from_counts) and from_counts.config.motor_boards == 1


def test_a_named_kits_counts_are_checked_as_its_configuration_checks_them() -> None:
    from j5aio.board_kinds import KitDefinition

    too_many = KitDefinition("big", "too many motor boards", {"sr-motor": 100})
    with pytest.raises(ValueError, match="motor_boards must be between 0 and 99, not 100"):
        SimulatedKit(too_many)
    with pytest.raises(TypeError, match="time_scale must be a number, not str"):
        SimulatedKit("sr2019", time_scale="fast")  # type: ignore[arg-type]


def test_kit_config_is_the_kit_modules_own() -> None:
    from j5aio.simulator import kit
    from j5aio.simulator._kit_config import KitConfig

    assert kit.KitConfig is KitConfig
    assert "KitConfig" in dir(kit) and "SimulatedKit" in dir(kit)
    assert KitConfig.__module__ == "j5aio.simulator.kit"
    assert kit._is_kit_config(KitConfig())
    assert not kit._is_kit_config("default")
    assert use_kit(KitConfig(sb_arduinos=0)).config.sb_arduinos == 0
    with pytest.raises(AttributeError, match="has no attribute 'NoSuchThing'"):
        kit.NoSuchThing  # noqa: B018
