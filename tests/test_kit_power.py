"""Tests of KitRobot powering the kit up, and of what it says about boards without power."""

from __future__ import annotations

import warnings

import pytest

from j5aio import environments, kit_power
from j5aio.boards.sr.v4 import (
    MotorBoardFw4,
    PowerBoardOutput,
    PowerOutputPosition,
    ServoBoardFw4,
)
from j5aio.environments import ENVIRONMENT_VARIABLE
from j5aio.errors import CommunicationTimeoutError
from j5aio.kit import KitRobot
from j5aio.kit_power import DEFAULT_POWER_ON, KitPowerWarning, check_power_on
from j5aio.power_outputs import BRAIN_OUTPUT, output_name, output_number
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import SimulatedKit, use_kit
from j5aio.simulator.loads import BATTERY_INTERNAL_RESISTANCE, MOTOR_FULL_POWER_CURRENT

KITS = ["default", "sr2019", "sb2019", "sr2023", "sb2024"]


@pytest.fixture(autouse=True)
def _fresh(monkeypatch: pytest.MonkeyPatch, fresh_kit: None) -> None:
    monkeypatch.delenv(ENVIRONMENT_VARIABLE, raising=False)
    monkeypatch.setattr(environments, "_hint_shown", False)


def drive_powers(kit: SimulatedKit) -> list[float]:
    return [motor.power for board in kit.drive_motor_boards for motor in board.motors]


@pytest.mark.parametrize("name", KITS)
async def test_start_up_switches_on_every_output_but_the_brains(name: str) -> None:
    kit = use_kit(name)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        outputs = kit.wiring.power_board.outputs if kit.wiring else ()
        # Every output on: L2 too, which a fw 4 board keeps on by itself and a fw 3
        # board (no brain output) leaves off.
        expected = [n != BRAIN_OUTPUT for n in range(len(outputs))]
        if len(outputs) == 7:
            expected[BRAIN_OUTPUT] = True
        assert list(outputs) == expected
        assert all(board.powered for board, _ in kit.wiring.feeds) if kit.wiring else False
        assert len(robot.motor_boards) == len(kit.drive_motor_boards)
        # With the outputs on, the motors move.
        for board in robot.motor_boards:
            for motor in board.motors:
                await motor.set_power(0.5)
        assert all(power == pytest.approx(0.5) for power in drive_powers(kit))


@pytest.mark.parametrize("name", KITS)
async def test_with_the_outputs_off_motors_do_not_move_and_a_warning_names_the_output(
    name: str,
) -> None:
    kit = use_kit(name)
    with pytest.warns(KitPowerWarning) as caught:
        async with KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=False) as robot:
            assert kit.wiring is not None
            assert not any(kit.wiring.power_board.outputs[n] for n in (0, 1, 2, 3, 5))
            assert len(robot.motor_boards) == 0
            with pytest.raises(IndexError, match=r"robot\.motor_boards is empty.*output H0"):
                await robot.motor_boards[0].motors[0].set_power(1)
    assert all(power == 0 for power in drive_powers(kit))
    texts = [str(warning.message) for warning in caught]
    assert any("motor board SIMMB0 is plugged in but does not answer" in text for text in texts)
    assert any("SIMMB0" in text and "output H0" in text for text in texts), texts
    # The servo board has no power either: its output is named too.
    assert any("SIMSB0" in text and "output L0" in text for text in texts), texts


async def test_the_outputs_to_switch_on_can_be_chosen() -> None:
    kit = use_kit("sr2023")
    with pytest.warns(KitPowerWarning, match="servo board SIMSB0 reports no 12 V.*L0"):
        async with KitRobot(
            environment=SIMULATED_ENVIRONMENT, power_on=[PowerBoardOutput.H0, "l3"]
        ) as robot:
            assert kit.wiring is not None
            assert kit.wiring.power_board.outputs == (
                True, False, False, False, True, True, False,
            )
            assert len(robot.motor_boards) == 1
            servo_board = robot.servo_boards[0]
            assert isinstance(servo_board, ServoBoardFw4)
            assert not await servo_board.power_good.get_state()


async def test_a_fw3_power_board_skips_the_5v_output_it_does_not_have() -> None:
    kit = use_kit("sr2019")
    async with KitRobot(
        environment=SIMULATED_ENVIRONMENT, power_on=[PowerOutputPosition.H0, 6, "L0"]
    ):
        assert kit.power_boards[0].outputs == (True, False, True, False, False, False)


async def test_full_motor_load_sags_the_battery_by_what_the_model_says() -> None:
    use_kit("sr2023")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        battery = robot.power_board.battery_sensor
        idle = await battery.get_voltage()
        for motor in robot.motor_boards[0].motors:
            await motor.set_power(1.0)
        loaded = await battery.get_voltage()
        load = 2 * MOTOR_FULL_POWER_CURRENT
        assert idle - loaded == pytest.approx(load * BATTERY_INTERNAL_RESISTANCE, abs=0.002)
        assert await battery.get_current() == pytest.approx(load, abs=0.002)
        assert await robot.power_board.outputs[0].get_current() == pytest.approx(load)


async def test_switching_an_output_off_later_silences_its_board() -> None:
    kit = use_kit("sr2023")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        await robot.power_board.outputs[0].set_is_enabled(False)
        assert drive_powers(kit) == [0.0, 0.0]  # unpowered: the motors coast


async def test_the_wait_for_the_boards_to_boot_follows_the_kits_time_scale(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    use_kit("sr2019", time_scale=0.01)
    waits: list[float] = []
    real_boot_wait = kit_power.boot_wait

    def recording_boot_wait(environment: object, seconds: float) -> float:
        waits.append(real_boot_wait(environment, seconds))
        return waits[-1]

    monkeypatch.setattr(kit_power, "boot_wait", recording_boot_wait)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", KitPowerWarning)
        async with KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=()):
            pass
    assert waits == []  # nothing switched on: nothing to wait for
    async with KitRobot(environment=SIMULATED_ENVIRONMENT):
        pass
    assert waits == [pytest.approx(KitRobot.POWER_UP_WAIT * 0.01)]


@pytest.mark.parametrize(
    ("power_on", "error", "match"),
    [
        (["L2"], ValueError, "cannot include L2"),
        ([4], ValueError, "cannot include L2"),
        (["H7"], ValueError, "no output 'H7'"),
        ([7], ValueError, "no output 7"),
        ("H0", TypeError, "power_on is True"),
        (3, TypeError, "power_on is True"),
        ([1.5], TypeError, "a power output is a name"),
    ],
)
def test_a_bad_power_on_is_refused_before_anything_is_sent(
    power_on: object, error: type[Exception], match: str
) -> None:
    with pytest.raises(error, match=match):
        KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=power_on)  # type: ignore[arg-type]
    KitRobot(environment=SIMULATED_ENVIRONMENT).release_lock()  # the lock was given back


def test_power_on_choices() -> None:
    assert check_power_on(True) == DEFAULT_POWER_ON == (0, 1, 2, 3, 5, 6)
    assert check_power_on(None) == DEFAULT_POWER_ON
    assert check_power_on(False) == ()
    assert check_power_on(["h1", 0, "H1", "5V", "five_volt"]) == (1, 0, 6)


def test_output_names_and_numbers() -> None:
    assert [output_number(name) for name in ("H0", " l3 ", "5v", "FIVE_VOLT")] == [0, 5, 6, 6]
    assert output_number(2) == 2
    assert output_name(4) == "L2"
    with pytest.raises(ValueError, match="has H0, H1, L0, L1, L2, L3 "):
        output_number("5V", count=6)
    with pytest.raises(TypeError, match="not bool"):
        output_number(True)


def test_power_hints_name_the_output_when_it_is_known() -> None:
    assert "output L1" in kit_power.power_hint(3)
    assert "outputs[3]" in kit_power.power_hint(3)
    assert "the power board output that feeds" in kit_power.power_hint(None)


async def test_on_another_environment_no_ports_are_looked_at() -> None:
    assert await kit_power.silent_motor_boards(object(), []) == []
    assert kit_power.unpowered_simulated_boards(object()) == []
    assert kit_power.boot_wait(object(), 0.5) == 0.5


async def test_on_the_hardware_the_motor_ports_are_listed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.backends.hardware.transports import discovery
    from j5aio.backends.hardware.transports.discovery import PortInfo

    ports = [
        PortInfo("/dev/ttyUSB0", 0x0403, 0x6001, "SR0A", "Student Robotics", "MCV4B", ""),
        PortInfo("/dev/ttyUSB1", 0x0403, 0x6001, "SR0B", "Student Robotics", "MCV4B", ""),
        PortInfo("/dev/ttyACM0", 0x2341, 0x0043, "ARD", "Arduino", "Uno", ""),
    ]
    monkeypatch.setattr(discovery, "_pyserial_comports", lambda: ports)
    hardware = environments.hardware_environment()
    assert await kit_power.silent_motor_boards(hardware, ["SR0B"]) == ["SR0A"]


def test_a_kit_file_names_the_outputs_on_the_robot(
    tmp_path: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> None:
    from pathlib import Path

    file = Path(str(tmp_path)) / "robot.toml"
    file.write_text(
        '[[board]]\nsimulator = "sr-motor-fw4"\nserial = "SR0UK1L"\noutput = "H1"\n'
    )
    monkeypatch.setenv("J5AIO_KIT_FILE", str(file))
    assert kit_power.feeding_outputs(environments.hardware_environment()) == {"SR0UK1L": 1}
    assert kit_power.output_feeding("SR0UK1L") == 1
    assert kit_power.output_feeding("NOT-IN-THE-FILE") is None
    with pytest.warns(KitPowerWarning, match="SR0UK1L .* output H1") as caught:
        messages = kit_power.warn_unpowered(["SR0UK1L"], [], {"SR0UK1L": 1})
    assert len(messages) == len(caught) == 1


async def test_an_unwired_kit_powers_its_boards_whatever_the_outputs_do() -> None:
    kit = use_kit("sr2019", wired=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error", KitPowerWarning)  # no board is without power
        async with KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=False) as robot:
            assert kit.power_boards[0].outputs == (False,) * 6
            assert len(robot.motor_boards) == len(robot.servo_boards) == 1
    assert kit_power.unpowered_simulated_boards(SIMULATED_ENVIRONMENT) == []
    assert kit_power.feeding_outputs(SIMULATED_ENVIRONMENT) == {}


def test_the_console_kit_says_it_powers_the_boards_up(tmp_path: pytest.TempPathFactory) -> None:
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    env = {**os.environ, "J5AIO_ENV": "console", "PYTHONPATH": str(root)}
    program = "from j5aio.sync import KitRobot\nKitRobot(power_on=['H0', 'L1'])\n"
    result = subprocess.run(
        [sys.executable, "-c", program], input="\n" * 20, capture_output=True, text=True,
        env=env, cwd=str(tmp_path), timeout=60, check=False,
    )
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[:3] == [
        "PowerBoard(SERIAL): Setting output 0 to True",
        "PowerBoard(SERIAL): Setting output 3 to True",
        "PowerBoard(SERIAL): Switched on outputs H0, L1 to power the kit's boards (L2 powers "
        "the brain); waiting 0.5 s for them to boot",
    ]


async def test_a_motor_board_losing_its_power_says_which_output_to_switch_on() -> None:
    use_kit("sr2023")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        motor_board = robot.motor_boards[0]
        assert isinstance(motor_board, MotorBoardFw4)
        motor = motor_board.motors[0]
        await motor.set_power(0.5)
        await robot.power_board.outputs[0].set_is_enabled(False)  # H0
        with pytest.raises(CommunicationTimeoutError, match=r"lost its 12 V .* output H0"):
            await motor.set_power(0.5)
        with pytest.raises(CommunicationTimeoutError, match="output H0"):
            await motor.get_current()
        await robot.power_board.outputs[0].set_is_enabled(True)
        await motor.set_power(0.25)  # it booted again, and answers
        assert kit_power.output_feeding("SIMMB0") == 0
