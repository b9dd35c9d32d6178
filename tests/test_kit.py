"""Tests of KitRobot."""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from j5aio import environments
from j5aio.backends.environment import Environment
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.boards.board import Board
from j5aio.boards.sr.kch import Colour, KCHBoard
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.environments import ENVIRONMENT_VARIABLE
from j5aio.errors import CommunicationError
from j5aio.kit import KitRobot
from j5aio.simulator.environment import (
    SIMULATED_BACKENDS,
    SIMULATED_ENVIRONMENT,
    SimulatedUSBDevice,
    SRV4PowerBoardSimulatedBackend,
)
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.kit import KitConfig, SimulatedKit, current_kit, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator


@pytest.fixture(autouse=True)
def _fresh(monkeypatch: pytest.MonkeyPatch, fresh_kit: None) -> None:
    monkeypatch.delenv(ENVIRONMENT_VARIABLE, raising=False)
    monkeypatch.setattr(environments, "_hint_shown", False)


def nothing_plugged_in_environment() -> Environment:
    """An environment like the hardware one, on a computer with no boards."""
    use_kit(KitConfig(0, 0, 0, 0, 0))
    environment = Environment("EmptyHardware")
    for backend in SIMULATED_BACKENDS:
        environment.register_backend(backend)
    return environment


async def test_finds_every_board_of_the_kit() -> None:
    kit = use_kit(KitConfig(ruggeduinos=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.environment is SIMULATED_ENVIRONMENT
        assert robot.power_board.serial_number == "SIMPB0"
        assert list(robot.power_boards) == [robot.power_board]
        assert [b.serial_number for b in robot.motor_boards] == ["SIMMB0", "SIMMB1"]
        assert [b.serial_number for b in robot.servo_boards] == ["SIMSB0"]
        assert [b.serial_number for b in robot.arduinos] == ["SIMSBA0"]
        assert [b.serial_number for b in robot.ruggeduinos] == ["SIMRD0"]
        await robot.motor_boards[1].motors[0].set_power(0.6)
        assert kit.motor_boards[1].motors[0].mode is MotorMode.FORWARD
    # Leaving the robot made every board safe: the motor boards brake, and then the
    # power board switched their 12 V off (the power board goes last).
    assert all(
        output.mode is MotorMode.BRAKE for board in kit.motor_boards for output in board.motors
    )
    assert kit.power_boards[0].outputs == (False,) * 6
    assert not any(board.powered for board in kit.motor_boards)


async def test_j5aio_env_chooses_the_simulated_kit(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "sim")
    use_kit(KitConfig(motor_boards=1))
    async with KitRobot() as robot:
        assert robot.environment is SIMULATED_ENVIRONMENT
        assert len(robot.motor_boards) == 1


async def test_a_missing_power_board_is_an_error_that_says_so() -> None:
    use_kit(KitConfig(power_boards=0))
    with pytest.raises(CommunicationError, match="expected exactly one PowerBoard"):
        async with KitRobot(environment=SIMULATED_ENVIRONMENT):
            pass  # pragma: no cover


async def test_the_lock_is_released_after_a_failed_setup() -> None:
    use_kit(KitConfig(power_boards=2))
    with pytest.raises(CommunicationError, match="found 2"):
        async with KitRobot(environment=SIMULATED_ENVIRONMENT):
            pass  # pragma: no cover
    use_kit()
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.power_board.serial_number == "SIMPB0"


async def test_no_boards_found_by_default_prints_one_hint(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr("j5aio.kit.get_default_environment", nothing_plugged_in_environment)
    for _ in range(2):
        with pytest.raises(CommunicationError, match="expected exactly one PowerBoard"):
            async with KitRobot():
                pass  # pragma: no cover
    err = capsys.readouterr().err
    assert err.count("j5aio: no boards found.") == 1
    assert "python -m j5aio run --sim" in err
    assert "J5AIO_ENV=sim" in err


async def test_no_hint_when_the_environment_was_passed_in(
    capsys: pytest.CaptureFixture[str],
) -> None:
    environment = nothing_plugged_in_environment()
    with pytest.raises(CommunicationError):
        async with KitRobot(environment=environment):
            pass  # pragma: no cover
    assert "no boards found" not in capsys.readouterr().err


async def test_no_hint_when_j5aio_env_chose_the_hardware(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "hardware")
    monkeypatch.setattr("j5aio.kit.get_default_environment", nothing_plugged_in_environment)
    with pytest.raises(CommunicationError):
        async with KitRobot():
            pass  # pragma: no cover
    assert "no boards found" not in capsys.readouterr().err


def test_environment_must_be_an_environment() -> None:
    with pytest.raises(TypeError, match=r"environment must be an Environment .* not str"):
        KitRobot(environment="sim")  # type: ignore[arg-type]
    # The lock was given back: another robot can be made.
    robot = KitRobot(environment=SIMULATED_ENVIRONMENT)
    robot.release_lock()


class PowerBoardGen2(PowerBoard):
    """A second generation of the power board: the same components, another protocol."""

    name = "Power Board (gen 2)"


GEN2_SIMULATOR = SRPowerBoardFw3Simulator("GEN2PB")


class PowerBoardGen2Backend(SRV4PowerBoardSimulatedBackend):
    """Finds the one gen 2 power board (standing in for a serial fw 4 board)."""

    board = PowerBoardGen2

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        kit = current_kit()
        return await super().discover(
            options=DiscoveryOptions(
                usb_finder=lambda **_: [SimulatedUSBDevice(GEN2_SIMULATOR, kit)]
            )
        )


def with_gen2(config: KitConfig) -> Environment:
    use_kit(config)
    environment = Environment.from_backends("Gen2", SIMULATED_BACKENDS)
    environment.register_backend(PowerBoardGen2Backend)
    return environment


async def test_a_second_generation_power_board_is_the_kits_power_board() -> None:
    environment = with_gen2(KitConfig(power_boards=0))
    async with KitRobot(environment=environment) as robot:
        assert isinstance(robot.power_board, PowerBoardGen2)
        assert robot.power_board.serial_number == "GEN2PB"
        # the environment's own power board backends (fw 3 and fw 4), then the added one
        assert robot.power_boards.backend_classes[0] is SRV4PowerBoardSimulatedBackend
        assert robot.power_boards.backend_classes[-1] is PowerBoardGen2Backend
        await robot.power_board.run_led.set_state(True)
        assert GEN2_SIMULATOR.run_led is True
        assert [b.serial_number for b in robot.motor_boards] == ["SIMMB0", "SIMMB1"]


async def test_both_generations_are_gathered_so_two_power_boards_are_an_error() -> None:
    environment = with_gen2(KitConfig(power_boards=1))
    robot = KitRobot(environment=environment)
    try:
        with pytest.raises(CommunicationError, match=r"one PowerBoard.*2 \(GEN2PB, SIMPB0\)"):
            await robot.setup()
        assert [type(b) for b in robot.power_boards] == [PowerBoardGen2, PowerBoard]
    finally:
        robot.release_lock()


@pytest.mark.parametrize("kit_name", ["sr2023", "sb2024"])
async def test_the_kch_of_the_kits_of_today_is_robot_kch(kit_name: str) -> None:
    kit = use_kit(kit_name)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert isinstance(robot.kch, KCHBoard)
        assert robot.kch.serial_number == "SIMKCH0"
        await robot.kch.leds[2].set_colour(Colour.MAGENTA)
        (simulator,) = kit.simulators("kch")
        assert isinstance(simulator, KCHSimulator)
        assert simulator.colours[2] == (True, False, True)


@pytest.mark.parametrize("kit", ["sr2019", "sb2019"])
async def test_a_kit_without_a_kch_has_none(kit: str) -> None:
    use_kit(kit)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.kch is None


async def test_an_environment_that_cannot_find_a_kch_has_none() -> None:
    use_kit("sr2023")
    environment = Environment("NoKCH")
    for backend in SIMULATED_BACKENDS:
        if backend.board is not KCHBoard:
            environment.register_backend(backend)
    async with KitRobot(environment=environment) as robot:
        assert robot.kch is None


@pytest.mark.parametrize(
    ("kit_name", "arduinos", "ruggeduinos"),
    [
        ("sr2023", ["SIMSRA0"], ["SIMSRA0"]),  # the SR Arduino (fw 2) is in both
        ("sb2024", ["SIMSBA0"], []),
        ("sb2019", ["SIMSBA0"], []),
        ("sr2019", [], ["SIMRD0"]),  # the Ruggeduino (fw 1) is j5's
    ],
)
async def test_robot_arduinos_holds_the_arduinos_of_every_firmware(
    kit_name: str, arduinos: list[str], ruggeduinos: list[str]
) -> None:
    use_kit(kit_name)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert [board.serial_number for board in robot.arduinos] == arduinos
        assert [board.serial_number for board in robot.ruggeduinos] == ruggeduinos
        for serial in arduinos:
            assert robot.arduinos[serial] is robot.arduinos[0]
            await robot.arduinos[0].pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
        if not arduinos:
            # An empty group names the groups that do have boards.
            with pytest.raises(IndexError, match=r"robot\.ruggeduinos \(1\)"):
                robot.arduinos[0]
            with pytest.raises(KeyError, match=r"robot\.arduinos is empty"):
                robot.arduinos["SIMRD0"]


async def test_looking_again_for_the_arduinos_asks_every_generation() -> None:
    kit = use_kit("sr2023")
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert len(robot.arduinos.backend_classes) == 2  # SourceBots 2019, and the rest
        kit.simulators("sr-arduino-fw2")[0].unplug()  # type: ignore[attr-defined]
        await robot.arduinos.update_boards()
        assert len(robot.arduinos) == 0


async def test_wait_for_start_waits_once_the_kit_is_powered_and_found(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.competition.metadata import METADATA_VARIABLE
    from j5aio.competition.start import clear_trigger, trigger_start

    monkeypatch.delenv(METADATA_VARIABLE, raising=False)
    clear_trigger()
    kit = use_kit(SimulatedKit(KitConfig(motor_boards=1), wired=True))
    trigger_start()  # as the button would, while the robot waits
    async with KitRobot(environment=SIMULATED_ENVIRONMENT, wait_for_start=True) as robot:
        assert robot.started
        # the kit was powered before the start: the motor board answers
        await robot.motor_boards[0].motors[0].set_power(0.5)
        assert kit.motor_boards[0].motors[0].power != 0
    with pytest.raises(TypeError, match="wait_for_start must be True or False"):
        KitRobot(wait_for_start="yes")  # type: ignore[arg-type]
