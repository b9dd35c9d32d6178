"""Tests of choosing the environment (J5AIO_ENV) and of the no-hardware hint."""

from __future__ import annotations

import io
import sys
from collections.abc import Sequence

import pytest

from j5aio import environments
from j5aio.backends.console import CONSOLE_ENVIRONMENT
from j5aio.backends.environment import Environment
from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.environments import (
    ENVIRONMENT_VARIABLE,
    environment_was_chosen,
    get_default_environment,
    get_environment,
    hint_no_hardware,
    no_hardware_hint,
)
from j5aio.errors import CommunicationError
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT, SRV4PowerBoardSimulatedBackend
from j5aio.simulator.kit import KitConfig, use_kit


@pytest.fixture(autouse=True)
def _fresh(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(ENVIRONMENT_VARIABLE, raising=False)
    monkeypatch.setattr(environments, "_hint_shown", False)


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("hardware", HARDWARE_ENVIRONMENT),
        ("sim", SIMULATED_ENVIRONMENT),
        ("console", CONSOLE_ENVIRONMENT),
        (" SIM ", SIMULATED_ENVIRONMENT),
    ],
)
def test_environments_by_name(name: str, expected: object) -> None:
    assert get_environment(name) is expected


def test_an_unknown_name_is_refused_with_the_choices() -> None:
    with pytest.raises(
        ValueError, match="unknown environment 'simulator': choose one of hardware, sim, console"
    ):
        get_environment("simulator")


def test_a_name_must_be_a_string() -> None:
    with pytest.raises(TypeError, match="an environment name must be a str, not int"):
        get_environment(3)  # type: ignore[arg-type]


def test_hardware_is_the_default(monkeypatch: pytest.MonkeyPatch) -> None:
    default = get_default_environment()
    assert default.name == HARDWARE_ENVIRONMENT.name
    assert default.board_backend_mapping == HARDWARE_ENVIRONMENT.board_backend_mapping
    assert default.backends == HARDWARE_ENVIRONMENT.backends
    assert not environment_was_chosen()
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "  ")
    assert get_default_environment() is default
    assert not environment_was_chosen()


class UnreachablePowerBoardBackend(SRV4PowerBoardSimulatedBackend):
    """A power board backend whose bus cannot be scanned (no USB library, say)."""

    @classmethod
    async def discover(cls, **kwargs: object) -> Sequence[Board]:
        raise CommunicationError("pyusb found no libusb backend")


def unreachable_hardware() -> Environment:
    environment = Environment("HardwareEnvironment")
    environment.register_backend(UnreachablePowerBoardBackend)
    return environment


async def test_hardware_that_cannot_be_looked_at_by_default_gets_the_hint(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(environments, "hardware_environment", unreachable_hardware)
    monkeypatch.setattr(
        environments, "_hardware_by_default", environments._hardware_by_default.__wrapped__
    )
    with pytest.raises(CommunicationError, match="libusb"):
        await get_default_environment().get_board_group(PowerBoard)
    assert capsys.readouterr().err.startswith("j5aio: no boards found.")


async def test_hardware_chosen_explicitly_gets_no_hint(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # The table of names is what an explicit choice looks up; patching it (not the
    # module's function) keeps the real USB bus out of this test, libusb or not.
    monkeypatch.setitem(environments._ENVIRONMENTS, "hardware", unreachable_hardware)
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "hardware")
    with pytest.raises(CommunicationError, match="libusb"):
        await get_default_environment().get_board_group(PowerBoard)
    assert capsys.readouterr().err == ""


async def test_boards_found_by_default_are_the_hardware_backends_boards() -> None:
    kit = use_kit(KitConfig(motor_boards=1))
    try:
        default = environments._HardwareByDefault(SIMULATED_ENVIRONMENT)
        group = await default.get_board_group(MotorBoard)
        assert [board.serial_number for board in group] == [kit.motor_boards[0].serial_number]
    finally:
        for board in list(Board.BOARDS):
            await board.close()


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("hardware", HARDWARE_ENVIRONMENT),
        ("sim", SIMULATED_ENVIRONMENT),
        ("console", CONSOLE_ENVIRONMENT),
    ],
)
def test_j5aio_env_chooses_the_default(
    monkeypatch: pytest.MonkeyPatch, value: str, expected: object
) -> None:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, value)
    assert get_default_environment() is expected
    assert environment_was_chosen()


def test_a_bad_j5aio_env_says_what_is_allowed(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "simulated")
    with pytest.raises(
        ValueError,
        match="J5AIO_ENV='simulated' is not an environment: set it to one of hardware, sim, con",
    ):
        get_default_environment()


def test_the_hint_names_the_running_program(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(sys, "argv", ["/home/me/robot.py"])
    assert no_hardware_hint() == (
        "j5aio: no boards found. To try your program without hardware: "
        "python -m j5aio run --sim robot.py (or set J5AIO_ENV=sim)"
    )
    monkeypatch.setattr(sys, "argv", ["-c"])
    assert "run --sim program.py" in no_hardware_hint()
    monkeypatch.setattr(sys, "argv", [])
    assert "run --sim program.py" in no_hardware_hint()


def test_the_hint_is_printed_once(capsys: pytest.CaptureFixture[str]) -> None:
    assert hint_no_hardware() is True
    assert hint_no_hardware() is False
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("j5aio: no boards found.") == 1
    assert captured.err.endswith("\n")
    assert captured.err.count("\n") == 1


def test_the_hint_is_not_printed_when_the_environment_was_chosen(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "hardware")
    out = io.StringIO()
    assert hint_no_hardware(file=out) is False
    assert out.getvalue() == ""


def test_the_hint_goes_where_it_is_told() -> None:
    out = io.StringIO()
    assert hint_no_hardware(file=out) is True
    assert out.getvalue().startswith("j5aio: no boards found.")


async def test_an_empty_search_by_default_gets_the_hint_naming_the_board(
    capsys: pytest.CaptureFixture[str],
) -> None:
    use_kit(KitConfig(power_boards=0, motor_boards=1))
    try:
        default = environments._HardwareByDefault(SIMULATED_ENVIRONMENT)
        assert len(await default.get_board_group(PowerBoard)) == 0
        err = capsys.readouterr().err
        assert err.startswith("j5aio: no Student Robotics v4 Power Board found. To try your")
        assert "run --sim" in err
    finally:
        for board in list(Board.BOARDS):
            await board.close()


async def test_no_hint_once_a_board_was_found(capsys: pytest.CaptureFixture[str]) -> None:
    use_kit(KitConfig(power_boards=0, motor_boards=1))
    try:
        default = environments._HardwareByDefault(SIMULATED_ENVIRONMENT)
        assert len(await default.get_board_group(MotorBoard)) == 1
        assert len(await default.get_board_group(PowerBoard)) == 0
        assert capsys.readouterr().err == ""
    finally:
        for board in list(Board.BOARDS):
            await board.close()
