"""Tests of the simulated kit's configuration and the current-kit registry."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from j5aio.simulator import kit as kit_module
from j5aio.simulator.clock import ManualClock
from j5aio.simulator.kit import KitConfig, SimulatedKit, current_kit, use_kit
from j5aio.simulator.sb_arduino_2019 import SBArduinoSimulator
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator


@pytest.fixture(autouse=True)
def _no_current_kit() -> Iterator[None]:
    saved = kit_module._current
    kit_module._current = None
    yield
    kit_module._current = saved


def test_the_default_kit_has_one_power_two_motor_one_servo_one_arduino() -> None:
    kit = SimulatedKit()
    assert kit.config == KitConfig()
    assert [type(b) for b in kit.power_boards] == [SRPowerBoardFw3Simulator]
    assert [type(b) for b in kit.motor_boards] == [SRMotorBoardFw3Simulator] * 2
    assert [type(b) for b in kit.servo_boards] == [SRServoBoardFw2Simulator]
    assert [type(b) for b in kit.sb_arduinos] == [SBArduinoSimulator]
    assert kit.ruggeduinos == ()
    assert len(kit) == 5
    assert kit.time_scale == 0.0


def test_serial_numbers_are_distinct_and_sort_in_board_order() -> None:
    kit = SimulatedKit(KitConfig(motor_boards=12, ruggeduinos=2))
    serials = [board.serial_number for board in kit]
    assert len(set(serials)) == len(serials)
    motor_serials = [board.serial_number for board in kit.motor_boards]
    assert motor_serials == sorted(motor_serials)
    assert motor_serials[0] == "SIMMB00"
    assert motor_serials[11] == "SIMMB11"
    assert [b.serial_number for b in kit.ruggeduinos] == ["SIMRD0", "SIMRD1"]
    assert all(isinstance(b, SRRuggeduinoSimulator) for b in kit.ruggeduinos)
    assert kit.power_boards[0].serial_number == "SIMPB0"
    assert kit.servo_boards[0].serial_number == "SIMSB0"
    assert kit.sb_arduinos[0].serial_number == "SIMSBA0"


def test_boards_are_grouped_by_how_they_connect() -> None:
    kit = SimulatedKit(KitConfig(ruggeduinos=1))
    assert set(kit.usb_simulators()) == {*kit.power_boards, *kit.servo_boards}
    assert set(kit.serial_simulators()) == {
        *kit.motor_boards,
        *kit.sb_arduinos,
        *kit.ruggeduinos,
    }
    assert len(list(kit)) == len(kit) == 6


def test_an_empty_kit_is_allowed() -> None:
    kit = SimulatedKit(KitConfig(0, 0, 0, 0, 0))
    assert len(kit) == 0
    assert f"<SimulatedKit {kit.name} KitConfig(power_boards=0" in repr(kit)


def test_each_kit_has_its_own_name() -> None:
    names = {SimulatedKit().name for _ in range(3)}
    assert len(names) == 3
    assert all(name.startswith("kit") for name in names)


@pytest.mark.parametrize("field", ["power_boards", "motor_boards", "sb_arduinos"])
@pytest.mark.parametrize("value", [-1, 100])
def test_counts_out_of_range_are_refused(field: str, value: int) -> None:
    with pytest.raises(ValueError, match=f"{field} must be between 0 and 99, not {value}"):
        KitConfig(**{field: value})


@pytest.mark.parametrize("value", [1.5, "2", True, None])
def test_counts_must_be_ints(value: object) -> None:
    with pytest.raises(TypeError, match="servo_boards must be an int, not"):
        KitConfig(servo_boards=value)  # type: ignore[arg-type]


def test_time_scale_must_be_a_non_negative_number() -> None:
    assert KitConfig(time_scale=1).time_scale == 1
    with pytest.raises(ValueError, match=r"time_scale must be 0 or more, not -0\.5"):
        KitConfig(time_scale=-0.5)
    with pytest.raises(ValueError, match="time_scale must be 0 or more, not nan"):
        KitConfig(time_scale=float("nan"))
    with pytest.raises(TypeError, match="time_scale must be a number, not str"):
        KitConfig(time_scale="fast")  # type: ignore[arg-type]


def test_current_kit_is_made_on_first_use_and_kept() -> None:
    first = current_kit()
    assert first.config == KitConfig()
    assert current_kit() is first


def test_use_kit_replaces_the_current_kit() -> None:
    made = use_kit(KitConfig(motor_boards=1))
    assert current_kit() is made
    assert len(made.motor_boards) == 1
    ready = SimulatedKit()
    assert use_kit(ready) is ready
    assert current_kit() is ready
    fresh = use_kit()
    assert fresh is not ready
    assert fresh.config == KitConfig()


def test_use_kit_refuses_other_things() -> None:
    with pytest.raises(TypeError, match=r"use_kit takes a KitConfig, .* SimulatedKit, not dict"):
        use_kit({"motor_boards": 1})  # type: ignore[arg-type]


@pytest.mark.parametrize("kit_name", ["sr2019", "sr2023", "sb2024"])
async def test_the_world_moves_by_the_motor_boards_of_every_generation(kit_name: str) -> None:
    from j5aio.kit import KitRobot
    from j5aio.simulator.arena import Pose
    from j5aio.simulator.camera import update_world
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    kit = use_kit(kit_name)
    clock = ManualClock()
    kit.use_clock(clock)  # the world moves only when the test moves the clock on
    assert len(kit.drive_motor_boards) == 1 if kit_name != "sr2019" else 2
    kit.world.place_robot(Pose(2875.0, 1000.0, 0.0))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        motors = robot.motor_boards[0].motors
        await motors[0].set_power(0.5)
        await motors[1].set_power(0.5)
        assert [m.power for m in kit.drive_motor_boards[0].motors] == [0.5, 0.5]
        update_world(kit)
        clock.advance(1.0)
        update_world(kit)  # one second of the kit's time at half power, straight ahead
        await motors[0].set_power(0)
        await motors[1].set_power(0)
    moved = math.dist((kit.world.pose.x, kit.world.pose.y), (2875.0, 1000.0))
    assert moved > 0.4 * kit.world.drive.max_speed


def test_the_drive_motor_boards_are_those_of_either_firmware() -> None:
    from j5aio.simulator.sr_motor_fw4 import SRMotorBoardFw4Simulator

    fw4_kit = SimulatedKit("sr2023")
    assert [type(board) for board in fw4_kit.drive_motor_boards] == [SRMotorBoardFw4Simulator]
    fw3_kit = SimulatedKit(KitConfig(motor_boards=2))
    assert [board.serial_number for board in fw3_kit.drive_motor_boards] == ["SIMMB0", "SIMMB1"]
    assert all(isinstance(b, SRMotorBoardFw3Simulator) for b in fw3_kit.drive_motor_boards)
