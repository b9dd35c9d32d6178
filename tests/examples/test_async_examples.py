"""The async examples, on the simulated kit: in this process against a scripted kit, and
as ``python -m j5aio run --sim`` runs them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from types import ModuleType

import anyio
import pytest

from j5aio.environments import ENVIRONMENT_VARIABLE
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode
from tests.module_from_file import load_module

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def load(name: str) -> ModuleType:
    return load_module(name, EXAMPLES / f"{name}.py")


@pytest.fixture
def kit(monkeypatch: pytest.MonkeyPatch, fresh_kit: None) -> SimulatedKit:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "sim")
    return use_kit(KitConfig())


def braked(kit: SimulatedKit) -> bool:
    return all(m.mode is MotorMode.BRAKE for m in kit.motor_boards[0].motors)


async def test_obstacle_stop_brakes_at_the_obstacle(kit: SimulatedKit) -> None:
    example = load("async_obstacle_stop")
    arduino = kit.sb_arduinos[0]

    async def wall_comes_near() -> None:
        await anyio.sleep(0.3)
        assert all(m.mode is MotorMode.FORWARD for m in kit.motor_boards[0].motors)
        arduino.set_ultrasound_distance(example.TRIGGER_PIN, example.ECHO_PIN, 0.2)

    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(wall_comes_near)
            with anyio.fail_after(5):
                distance = await example.drive_until_obstacle(robot, longest=10)
        assert distance == pytest.approx(0.2, abs=0.01)
        assert braked(kit)


async def test_obstacle_stop_gives_up_after_its_longest_drive(kit: SimulatedKit) -> None:
    example = load("async_obstacle_stop")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        start = anyio.current_time()
        assert await example.drive_until_obstacle(robot, longest=0.3) is None
        assert anyio.current_time() - start >= 0.3
        assert braked(kit)


async def test_obstacle_stop_brakes_when_cancelled(kit: SimulatedKit) -> None:
    example = load("async_obstacle_stop")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        with anyio.move_on_after(0.2):
            await example.drive_until_obstacle(robot, longest=10)
        assert braked(kit)


async def test_status_task_blinks_beeps_and_turns_the_led_off(kit: SimulatedKit) -> None:
    example = load("async_status_lights")
    power = kit.power_boards[0]
    seen: set[bool] = set()
    frequencies: set[int] = set()

    async def watch() -> None:
        while True:
            seen.add(power.run_led)
            frequencies.update(note.frequency for note in power.note_queue)
            await anyio.sleep(0.01)

    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(watch)
            async with anyio.create_task_group() as inner:
                inner.start_soon(example.show_status, robot)
                await anyio.sleep(0.7)
                inner.cancel_scope.cancel()
            tasks.cancel_scope.cancel()
        assert seen == {True, False}
        assert power.run_led is False
        assert frequencies == {round(example.Note.A6)}


async def test_watchdog_drives_while_fed_and_brakes_when_the_sensor_falls_quiet(
    kit: SimulatedKit,
) -> None:
    example = load("async_watchdog")
    arduino = kit.sb_arduinos[0]
    arduino.set_ultrasound_distance(example.TRIGGER_PIN, example.ECHO_PIN, 1.0)
    quiet_from = 0.0

    async def sensor_falls_off() -> None:
        nonlocal quiet_from
        await anyio.sleep(0.8)
        assert all(m.mode is MotorMode.FORWARD for m in kit.motor_boards[0].motors)
        quiet_from = anyio.current_time()
        arduino.set_ultrasound_distance(example.TRIGGER_PIN, example.ECHO_PIN, None)

    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(sensor_falls_off)
            with anyio.fail_after(5):
                quiet = await example.guard(robot, quiet_after=0.3)
        bitten = anyio.current_time()
        assert quiet >= 0.3
        # it did not bite while the sensor talked (its last reading came just before)
        assert bitten - quiet_from >= 0.3 - 2 * example.READ_INTERVAL
        assert braked(kit)


async def test_manoeuvre_ends_early_at_a_wall(kit: SimulatedKit) -> None:
    example = load("async_timed_manoeuvre")
    arduino = kit.sb_arduinos[0]

    async def wall_appears() -> None:
        await anyio.sleep(0.3)
        arduino.set_ultrasound_distance(example.TRIGGER_PIN, example.ECHO_PIN, 0.3)

    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(wall_appears)
            start = anyio.current_time()
            assert await example.manoeuvre(robot, time_limit=5) is True
        assert anyio.current_time() - start < 2
        assert braked(kit)


async def test_manoeuvre_times_out_cancelling_both_tasks(kit: SimulatedKit) -> None:
    example = load("async_timed_manoeuvre")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert await example.manoeuvre(robot, time_limit=0.6) is False
        assert braked(kit)
        widths = kit.servo_boards[0].pulse_widths_us
        assert widths[0] is not None  # the flag waved


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("async_obstacle_stop", "Nothing came within 0.3 m in 2.0 s: braked."),
        ("async_status_lights", "Work done; the run LED is off."),
        ("async_watchdog", "motors braked."),
        ("async_timed_manoeuvre", "No wall within 1.5 s: gave up and braked."),
    ],
)
def test_runs_under_run_sim(name: str, expected: str) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", str(EXAMPLES / f"{name}.py")],
        capture_output=True, text=True, timeout=60, cwd=ROOT, check=False,
        env={**__import__("os").environ, "PYTHONPATH": str(ROOT)},
    )
    assert result.returncode == 0, result.stderr
    assert expected in result.stdout
