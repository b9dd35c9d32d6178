"""The simulated kit drives its boards' clocks: notes end and LEDs flash with no command."""

from __future__ import annotations

import pytest

from j5aio.boards.sr.v4 import PowerBoard, PowerBoardFw4
from j5aio.components.flashing_led import LEDMode
from j5aio.demo import describe_boards
from j5aio.simulator.clock import Clock, ClockedSimulator, ManualClock, ScaledClock
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator

pytestmark = pytest.mark.usefixtures("fresh_kit")


def _fw4_power(kit: SimulatedKit) -> SRPowerBoardFw4Simulator:
    (simulator,) = kit.simulators("sr-power-fw4")
    assert isinstance(simulator, SRPowerBoardFw4Simulator)
    return simulator


@pytest.mark.parametrize("kit_name", ["sr2019", "sb2019", "sr2023", "sb2024", "default"])
@pytest.mark.parametrize("time_scale", [0.0, 0.5, 2.0])
def test_every_board_that_keeps_time_follows_its_kit_clock(
    kit_name: str, time_scale: float
) -> None:
    kit = SimulatedKit(kit_name, time_scale=time_scale)
    assert isinstance(kit.clock, ScaledClock)
    assert kit.clock.time_scale == (time_scale or 1.0)  # a scale of 0 still runs in real time
    clocked = [sim for sim in kit if isinstance(sim, ClockedSimulator)]
    assert clocked  # every kit has a power board, whose firmware keeps time
    for simulator in clocked:
        assert simulator.clock is kit.clock
    manual = ManualClock()
    kit.use_clock(manual)
    now_followed: Clock = kit.clock
    assert now_followed is manual
    assert all(sim.clock is manual for sim in clocked)


def test_a_kit_config_time_scale_sets_the_clock() -> None:
    kit = SimulatedKit(KitConfig(time_scale=4))
    assert isinstance(kit.clock, ScaledClock) and kit.clock.time_scale == 4
    assert kit.power_boards[0].clock is kit.clock


async def test_a_short_note_has_ended_without_a_command_on_the_fw4_power_board() -> None:
    kit = use_kit("sr2023")
    clock = ManualClock()
    kit.use_clock(clock)
    simulator = _fw4_power(kit)
    clock.advance(1)  # the boot beep is over
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoardFw4)).singular()
    await board.piezo.buzz(0.15, 880)
    assert simulator.playing is not None and simulator.playing.frequency == 880
    clock.advance(0.1)
    assert simulator.playing is not None  # 50 ms to go
    assert "piezo 880 Hz" in describe_boards(kit)
    clock.advance(0.1)  # 0.2 s after the buzz
    assert simulator.playing is None
    assert "piezo quiet" in describe_boards(kit)


async def test_the_flashing_run_led_toggles_once_a_second_on_the_fw4_power_board() -> None:
    kit = use_kit("sr2023")
    clock = ManualClock()
    kit.use_clock(clock)
    simulator = _fw4_power(kit)
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoardFw4)).singular()
    await board.run_led.set_mode(LEDMode.FLASH)
    start = simulator.uptime
    clock.advance(1 - start % 1)  # to the start of the board's next second
    seen = []
    for _ in range(6):
        seen.append(simulator.run_led)
        clock.advance(0.5)
    lit, dark = seen[0], not seen[0]
    assert seen == [lit, lit, dark, dark, lit, lit]  # a toggle at each whole second
    assert simulator.led_modes[0] == "F"  # still flashing: nothing was sent


async def test_the_kit_scale_slows_the_board_time() -> None:
    kit = use_kit("sr2023", time_scale=2.0)

    class Real:
        now = 0.0

        def __call__(self) -> float:
            return self.now

    real = Real()
    kit.use_clock(ScaledClock(2.0, source=real))  # the kit's own clock, with a fake real time
    simulator = _fw4_power(kit)
    real.now = 1.0  # one real second: half a board second
    assert simulator.playing is None  # the 150 ms boot beep has ended
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoardFw4)).singular()
    await board.piezo.buzz(0.15, 440)
    real.now += 0.2  # 0.1 s of board time
    assert simulator.playing is not None
    real.now += 0.2  # 0.2 s of board time
    assert simulator.playing is None


async def test_queued_notes_play_out_on_the_fw3_power_board() -> None:
    kit = use_kit("sr2019")
    clock = ManualClock()
    kit.use_clock(clock)
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    await board.piezo.buzz(0.15, 880)
    assert "piezo 880 Hz" in describe_boards(kit)
    clock.advance(0.2)
    assert kit.power_boards[0].note_queue == []
    assert "piezo quiet" in describe_boards(kit)


async def test_the_robot_drives_in_the_kit_time() -> None:
    from j5aio.boards.sr.v4 import MotorBoard
    from j5aio.simulator.arena import Pose
    from j5aio.simulator.camera import update_world

    class Real:
        now = 0.0

        def __call__(self) -> float:
            return self.now

    real = Real()
    kit = use_kit(KitConfig(power_boards=0, motor_boards=1, servo_boards=0, sb_arduinos=0))
    kit.use_clock(ScaledClock(2.0, source=real))  # a time scale of 2: half speed
    kit.world.place_robot(Pose(2875.0, 1000.0, 0.0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    await board.motors[0].set_power(0.5)
    await board.motors[1].set_power(0.5)
    update_world(kit)
    real.now += 2.0  # two real seconds: one second of the kit's time
    update_world(kit)
    await board.motors[0].set_power(0)
    await board.motors[1].set_power(0)
    # One kit second at half the full speed (heading 0 is along x), not two.
    moved = kit.world.pose.x - 2875.0
    assert moved == pytest.approx(0.5 * kit.world.drive.max_speed, rel=0.01)
