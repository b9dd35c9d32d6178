"""Tests of the demo robot (j5aio.demo)."""

from __future__ import annotations

import io

import pytest

from j5aio.demo import all_motors_braked, demo, describe_boards, run_demo
from j5aio.robot import BaseRobot, UnableToObtainLock
from j5aio.simulator.kit import KitConfig, SimulatedKit
from j5aio.simulator.sr_motor_fw3 import MotorMode

pytestmark = pytest.mark.usefixtures("fresh_kit")


async def test_the_demo_drives_senses_signals_and_ends_braked() -> None:
    out = io.StringIO()
    assert await demo(2.5, out=out) is True
    text = out.getvalue()
    lines = text.splitlines()
    assert lines[0].startswith("j5aio demo: a robot on the simulated kit for 2.5 s")
    assert "The kit: 'default': 1 x SR v4 power board" in lines[0]
    assert "2 x SR v4 motor board" in lines[0]
    assert "1 x SourceBots Arduino" in lines[0]
    # The three tasks ran side by side and talked to each other.
    assert "drive   forwards: both motors at +0.6" in text
    assert "sense   battery" in text
    assert "asking drive to turn" in text
    assert "drive   turning on the spot" in text
    assert "signal  beep" in text
    # The boards lines come from the simulators: the motors really drove, and turned.
    assert "SIMMB0 [forward 60%, forward 60%]" in text  # power 0.6 drives at 60 % duty
    assert "SIMMB0 [forward 50%, reverse 50%]" in text or "flag servo +1.0" in text
    assert lines[-1] == "The robot has stopped: every simulated motor is braked."
    final = lines[-3]
    # Braked, then the power board's safe state switched their 12 V off.
    assert "SIMMB0 [brake, brake] | SIMMB1 [brake, brake] | outputs on: none" in final


def test_run_demo_runs_it_in_its_own_event_loop() -> None:
    out = io.StringIO()
    assert run_demo(0.3, out=out) is True
    assert "every simulated motor is braked" in out.getvalue()


async def test_a_demo_that_could_not_start_does_not_warn_about_motors(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("J5AIO_LOCK_PORT", "0")
    holder = BaseRobot()
    assert holder._lock is not None
    monkeypatch.setenv("J5AIO_LOCK_PORT", str(holder._lock.getsockname()[1]))
    out = io.StringIO()
    try:
        with pytest.raises(UnableToObtainLock):
            await demo(0.3, out=out)
    finally:
        holder.release_lock()
    assert "left running" not in out.getvalue()
    assert "has stopped" not in out.getvalue()


@pytest.mark.parametrize("seconds", [0, -1.0, float("nan")])
async def test_the_run_time_must_be_positive(seconds: float) -> None:
    with pytest.raises(ValueError, match="seconds must be more than 0"):
        await demo(seconds, out=io.StringIO())


def test_all_motors_braked_reads_the_simulators() -> None:
    kit = SimulatedKit(KitConfig(motor_boards=2))
    # A motor board simulator starts coasting, until the host brakes it.
    assert not all_motors_braked(kit)
    brake_all = bytes([0x02, 2, 0x03, 2])  # fw 3: motor 0 brake, motor 1 brake
    kit.motor_boards[0].receive(brake_all)
    assert not all_motors_braked(kit)  # the second board still coasts
    kit.motor_boards[1].receive(brake_all)
    assert all_motors_braked(kit)
    kit.motor_boards[1].receive(bytes([0x03, 128 + 50]))  # motor 1 forwards
    assert kit.motor_boards[1].motors[1].mode is MotorMode.FORWARD
    assert not all_motors_braked(kit)
    kit.motor_boards[1].powered = False  # its 12 V is cut: it drives nothing
    assert all_motors_braked(kit)


def test_describe_boards_shows_the_power_outputs_and_the_battery() -> None:
    kit = SimulatedKit(wired=True)
    assert "outputs on: none, battery 12.00 V" in describe_boards(kit)
    kit.power_boards[0].ctrl_transfer(0x00, 64, 1, 0)  # H0 on: SIMMB0 powered
    assert "outputs on: H0, battery 12.00 V" in describe_boards(kit)  # motors still
    kit.motor_boards[0].receive(bytes([0x02, 128 + 100]))  # motor 0 at full power
    # 2.5 A through the battery's 0.05 ohm: 0.125 V less.
    assert "SIMMB0 [forward 100%, coast] | SIMMB1 [coast, coast]" in describe_boards(kit)
    assert "outputs on: H0, battery 11.88 V" in describe_boards(kit)


def test_describe_boards_shows_each_board() -> None:
    kit = SimulatedKit()
    line = describe_boards(kit)
    assert line.startswith("SIMMB0 [")
    assert "SIMMB1 [" in line
    assert "run LED on, piezo quiet" in line
    assert "flag servo +0.0" in line
    assert "wall" not in line


@pytest.mark.parametrize("kit", ["sr2019", "sb2019"])
async def test_the_demo_runs_on_each_named_kit_and_ends_braked(kit: str) -> None:
    out = io.StringIO()
    assert await demo(1.0, out=out, kit=kit) is True
    text = out.getvalue()
    assert f"The kit: '{kit}'" in text.splitlines()[0]
    assert "found 4 boards" in text
    assert "drive   forwards" in text
    assert ("Ruggeduino" in text) == (kit == "sr2019")


async def test_the_demo_follows_j5aio_kit(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("J5AIO_KIT", "sr2019")
    out = io.StringIO()
    assert await demo(0.3, out=out) is True
    assert "The kit: 'sr2019'" in out.getvalue()


async def test_the_demo_refuses_an_unknown_kit_listing_the_kits() -> None:
    with pytest.raises(ValueError, match="no kit called 'moon'; choose one of: default, sr2019"):
        await demo(1.0, out=io.StringIO(), kit="moon")


@pytest.mark.parametrize("kit", ["sr2023", "sb2024"])
async def test_the_demo_runs_on_todays_kits_sees_the_wall_and_ends_braked(kit: str) -> None:
    out = io.StringIO()
    assert await demo(4.0, out=out, kit=kit) is True
    text = out.getvalue()
    assert f"The kit: '{kit}'" in text.splitlines()[0]
    assert "drive   forwards" in text
    # The Arduino of today's kits measures the wall: drive turns when asked to.
    assert "m ahead: asking drive to turn" in text
    assert "flag servo" in text and "SIMMB0 [" in text
    last = text.strip().splitlines()[-3]
    assert "SIMMB0 [brake, brake] | outputs on: L2," in last  # the brain's stays on


async def test_on_the_sr2023_kit_the_demo_finds_the_kch_and_lights_its_leds() -> None:
    out = io.StringIO()
    assert await demo(4.0, out=out, kit="sr2023") is True
    text = out.getvalue()
    assert "found 5 boards" in text  # power, motor, servo, Arduino and the KCH
    # The boards lines read the simulated KCH's pins: drive lit LED A green, then yellow
    # while turning; signal lit LED B red while the wall was close.
    assert "KCH LEDs A green, B off, C off" in text
    assert "KCH LEDs A yellow" in text
    assert "B red" in text


def test_describe_boards_shows_the_kch_leds() -> None:
    kit = SimulatedKit("sr2023")
    assert describe_boards(kit).endswith("KCH LEDs A off, B off, C off")
    assert "KCH" not in describe_boards(SimulatedKit("sr2019"))
