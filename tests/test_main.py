"""Tests of the command line, ``python -m j5aio``."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import textwrap
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import serial

from j5aio.__main__ import SIMULATOR_NAMES, build_parser, main
from j5aio.backends.hardware import listing
from j5aio.backends.hardware.listing import FoundBoard
from j5aio.environments import ENVIRONMENT_VARIABLE
from j5aio.errors import CommunicationError
from j5aio.simulator.environment import kit_discovery_options
from j5aio.simulator.kit import KitConfig, SimulatedKit

REAL_FIND_BOARDS = listing.find_boards


@pytest.fixture(autouse=True)
def _fresh(monkeypatch: pytest.MonkeyPatch, fresh_kit: None) -> None:
    monkeypatch.delenv(ENVIRONMENT_VARIABLE, raising=False)
    monkeypatch.setattr(sys, "argv", list(sys.argv))
    monkeypatch.setattr(sys, "path", list(sys.path))


def python_m_j5aio(
    *args: str, cwd: Path | None = None, **variables: str
) -> subprocess.CompletedProcess[str]:
    environment = {
        k: v for k, v in os.environ.items() if k not in (ENVIRONMENT_VARIABLE, "J5AIO_KIT")
    }
    environment.update(variables)
    return subprocess.run(
        [sys.executable, "-m", "j5aio", *args],
        capture_output=True,
        text=True,
        timeout=60,
        env=environment,
        check=False,
        cwd=cwd,
    )


# --- help and usage ----------------------------------------------------------------------


def test_help_lists_every_command_with_examples(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    for command in ("list", "demo", "run", "simulate"):
        assert command in text
    assert "python -m j5aio run --sim robot.py" in text


def test_no_command_prints_the_help_and_fails(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2
    assert "usage: python -m j5aio" in capsys.readouterr().out


def test_simulate_help_lists_the_boards(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["simulate", "--help"])
    text = capsys.readouterr().out
    for name in SIMULATOR_NAMES:
        assert name in text


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["demo", "--seconds", "0"], "0 s is out of range: give 0 < S <= 600"),
        (["demo", "--seconds", "soon"], "'soon' is not a number of seconds"),
        (["simulate", "sb-arduino", "--time-scale", "-1"], "-1 is negative: give 0 or more"),
        (["simulate", "sb-arduino", "--time-scale", "x"], "'x' is not a number"),
        (["simulate", "sr-power"], "invalid choice: 'sr-power'"),
        (["run", "--sim", "--env", "console", "x.py"], "not allowed with argument"),
        (["run", "--env", "moon", "x.py"], "invalid choice: 'moon'"),
    ],
)
def test_bad_arguments_say_what_is_allowed(
    arguments: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(arguments)
    assert exit_info.value.code == 2
    assert message in capsys.readouterr().err


def test_the_parser_is_named_for_python_m() -> None:
    assert build_parser().prog == "python -m j5aio"


# --- list --------------------------------------------------------------------------------


def test_list_prints_each_board_found(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    kit = SimulatedKit(KitConfig())

    async def find_in_kit(*, problems: list[str]) -> list[FoundBoard]:
        return await REAL_FIND_BOARDS(options=kit_discovery_options(kit), problems=problems)

    monkeypatch.setattr(listing, "find_boards", find_in_kit)
    assert main(["list"]) == 0
    text = capsys.readouterr().out
    for simulator in kit:
        assert str(simulator.serial_number) in text
    assert "Student Robotics v4 Motor Board" in text
    assert f"sim://{kit.name}/SIMMB0" in text
    assert "5 boards found." in text


def test_list_says_plainly_when_there_are_none_and_what_it_looked_for(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    async def nothing(*, problems: list[str]) -> list[FoundBoard]:
        return []

    monkeypatch.setattr(listing, "find_boards", nothing)
    assert main(["list"]) == 0
    text = capsys.readouterr().out
    assert "No boards found." in text
    for kind in ("sr-v4-power-fw3", "sr-v4-motor-fw3", "sr-v4-servo-fw2", "sb-arduino-2019"):
        assert kind in text
    assert "SR Ruggeduino, firmware 1" in text


def test_list_reports_a_failure_to_look(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    async def broken(*, problems: list[str]) -> list[FoundBoard]:
        raise CommunicationError("serial ports could not be listed")

    monkeypatch.setattr(listing, "find_boards", broken)
    assert main(["list"]) == 1
    assert "j5aio: could not look for boards: serial ports could not be listed" in (
        capsys.readouterr().err
    )


def test_list_shows_what_it_found_and_says_what_it_could_not_look_for(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    async def partly(*, problems: list[str]) -> list[FoundBoard]:
        problems.append("Student Robotics v4 Power Board: pyusb found no libusb backend")
        return [FoundBoard("Student Robotics v4 Motor Board", "SR0ABC", "3", "/dev/ttyUSB0")]

    monkeypatch.setattr(listing, "find_boards", partly)
    assert main(["list"]) == 0
    captured = capsys.readouterr()
    assert "SR0ABC" in captured.out
    assert "could not look for every board: Student Robotics v4 Power Board: pyusb found no" in (
        captured.err
    )

    async def only_problems(*, problems: list[str]) -> list[FoundBoard]:
        problems.append("Student Robotics v4 Servo Board: pyusb found no libusb backend")
        return []

    monkeypatch.setattr(listing, "find_boards", only_problems)
    assert main(["list"]) == 1
    assert "No boards found." in capsys.readouterr().out


# --- run ---------------------------------------------------------------------------------


@pytest.fixture
def program(tmp_path: Path) -> Iterator[Path]:
    (tmp_path / "helper.py").write_text("GREETING = 'hello from a module beside it'\n")
    path = tmp_path / "robot.py"
    path.write_text(
        textwrap.dedent(
            """
            import os, sys
            import helper
            print("env", os.environ.get("J5AIO_ENV"))
            print("argv", sys.argv)
            print("name", __name__)
            print(helper.GREETING)
            """
        )
    )
    yield path


@pytest.mark.parametrize(
    ("flags", "environment"),
    [(["--sim"], "sim"), (["--env", "console"], "console"), ([], None)],
)
def test_run_runs_the_program_as_main_in_the_chosen_environment(
    program: Path,
    flags: list[str],
    environment: str | None,
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["run", *flags, str(program), "--fast", "3"]) == 0
    text = capsys.readouterr().out
    assert f"env {environment}" in text
    assert f"argv {[str(program), '--fast', '3']!r}" in text
    assert "name __main__" in text
    assert "hello from a module beside it" in text


def test_run_drops_a_separating_double_dash(
    program: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["run", "--sim", str(program), "--", "-x"]) == 0
    assert f"argv {[str(program), '-x']!r}" in capsys.readouterr().out


def test_run_refuses_a_missing_program(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    missing = tmp_path / "nope.py"
    assert main(["run", "--sim", str(missing)]) == 2
    assert f"j5aio: cannot run {missing}: no such file" in capsys.readouterr().err
    assert ENVIRONMENT_VARIABLE not in os.environ


KIT_PROGRAM = """
import anyio
from j5aio.kit import KitRobot

async def main():
    async with KitRobot() as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        print("environment", robot.environment.name)
        print("motor boards", [board.serial_number for board in robot.motor_boards])

anyio.run(main)
"""


def test_run_sim_runs_a_kit_robot_on_the_simulated_kit(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(KIT_PROGRAM)
    result = python_m_j5aio("run", "--sim", "robot.py", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "environment SimulatedEnvironment" in result.stdout
    assert "motor boards ['SIMMB0', 'SIMMB1']" in result.stdout


def test_a_program_finding_no_hardware_offers_the_sim_flag_in_one_line(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(KIT_PROGRAM)
    result = python_m_j5aio("run", "robot.py", cwd=tmp_path)
    assert result.returncode != 0
    hints = [line for line in result.stderr.splitlines() if line.startswith("j5aio: no ")]
    assert hints == [  # the first search that finds nothing says so (the power board's)
        "j5aio: no Student Robotics v4 Power Board found. To try your program without "
        "hardware: python -m j5aio run --sim robot.py (or set J5AIO_ENV=sim)"
    ]


# --- simulate ----------------------------------------------------------------------------


posix_only = pytest.mark.skipif(
    sys.platform == "win32", reason="pseudo-terminals exist on POSIX systems only"
)


@contextlib.contextmanager
def simulating(*args: str) -> Iterator[tuple[subprocess.Popen[str], str]]:
    """Run ``python -m j5aio simulate ARGS``; yield the process and the port it printed."""
    environment = {k: v for k, v in os.environ.items() if k != ENVIRONMENT_VARIABLE}
    process = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "simulate", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=environment,
    )
    try:
        assert process.stdout is not None
        yield process, process.stdout.readline().strip()
    finally:
        if process.poll() is None:  # only when the test failed
            process.kill()
        process.communicate(timeout=10)


def stop(process: subprocess.Popen[str], how: signal.Signals) -> str:
    """Stop a ``simulate`` process with a signal; return what it wrote to stderr."""
    process.send_signal(how)
    _, errors = process.communicate(timeout=10)
    assert process.returncode == 0
    return errors


@posix_only
def test_simulate_serves_a_motor_board_until_terminated() -> None:
    with simulating("sr-motor", "--serial-number", "MB42") as (process, path):
        with serial.Serial(path, 1_000_000, timeout=5) as port:
            port.write(b"\x01")  # fw 3: "what are you?"
            assert port.read(8) == b"MCV4B:3\n"
        errors = stop(process, signal.SIGTERM)
    assert "SR v4 motor board, firmware 3 (1 Mbaud) (serial number MB42)" in errors
    assert errors.rstrip().endswith("Stopped.")


@posix_only
def test_simulate_with_time_scale_zero_boots_at_once() -> None:
    with simulating("sr-ruggeduino", "--time-scale", "0") as (process, path):
        started = time.monotonic()
        with serial.Serial(path, 115200, timeout=5) as port:
            port.write(b"v")  # SR firmware: version
            assert port.readline() == b"SRduino:1\n"
        assert time.monotonic() - started < 1.0  # a real Ruggeduino takes 1.5 s to boot
        stop(process, signal.SIGINT)


# --- demo --------------------------------------------------------------------------------


def test_demo_in_process(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--seconds", "0.5"]) == 0
    assert "every simulated motor is braked" in capsys.readouterr().out


def test_demo_runs_end_to_end_ends_by_itself_and_leaves_every_motor_braked() -> None:
    started = time.monotonic()
    result = python_m_j5aio("demo")
    elapsed = time.monotonic() - started
    assert result.returncode == 0, result.stderr
    assert elapsed < 30
    lines = result.stdout.splitlines()
    assert lines[0].startswith("j5aio demo: a robot on the simulated kit for 6 s")
    assert any("drive   forwards" in line for line in lines)
    assert any("sense   battery" in line for line in lines)
    assert any("signal  beep" in line for line in lines)
    final_boards = [line for line in lines if "boards" in line][-1]
    assert "SIMMB0 [brake, brake] | SIMMB1 [brake, brake]" in final_boards
    assert lines[-1] == "The robot has stopped: every simulated motor is braked."


@posix_only
def test_an_interrupted_demo_still_leaves_every_motor_braked() -> None:
    environment = {k: v for k, v in os.environ.items() if k != ENVIRONMENT_VARIABLE}
    process = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "demo", "--seconds", "30"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=environment,
        # As in a terminal: Ctrl-C raises KeyboardInterrupt (a shell may have ignored it).
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        assert process.stdout is not None
        for line in process.stdout:
            if "SIMMB0 [forward" in line:  # the robot is driving
                break
        process.send_signal(signal.SIGINT)
        rest, errors = process.communicate(timeout=20)
    finally:
        if process.poll() is None:  # only when the test failed
            process.kill()
            process.communicate(timeout=10)
    assert process.returncode == 130
    assert errors.strip() == "Interrupted."
    lines = rest.splitlines()
    assert "SIMMB0 [brake, brake] | SIMMB1 [brake, brake]" in lines[-3]
    assert lines[-1] == "The robot has stopped: every simulated motor is braked."


# --- kits and simulator options ------------------------------------------------------------


def test_run_with_kit_chooses_the_simulated_environment_and_the_kit(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(
        KIT_PROGRAM + "\nimport os\nprint('kit', os.environ['J5AIO_KIT'])\n"
        "from j5aio.simulator.kit import current_kit\n"
        "print('ruggeduinos', len(current_kit().ruggeduinos))\n"
    )
    result = python_m_j5aio("run", "--kit", "sr2019", "robot.py", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "environment SimulatedEnvironment" in result.stdout
    assert "motor boards ['SIMMB0']" in result.stdout
    assert "kit sr2019" in result.stdout
    assert "ruggeduinos 1" in result.stdout


def test_j5aio_kit_chooses_the_kit_of_run_sim(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(KIT_PROGRAM)
    result = python_m_j5aio("run", "--sim", "robot.py", cwd=tmp_path, J5AIO_KIT="sb2019")
    assert result.returncode == 0, result.stderr
    assert "motor boards ['SIMMB0']" in result.stdout


def test_run_refuses_a_kit_on_another_environment(
    program: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["run", "--env", "console", "--kit", "sr2019", str(program)]) == 2
    assert "--kit chooses a simulated kit" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["demo", "--kit", "moon"], "no kit called 'moon'; choose one of: default, sr2019, sb2019"),
        (["run", "--kit", "moon", "x.py"], "no kit called 'moon'"),
        (["simulate", "sb-arduino", "--analog", "A6=1"], "'A6' is not an analogue pin: use A0"),
        (["simulate", "sb-arduino", "--analog", "A0=6"], "6 V is out of range: give 0 to 5 V"),
        (["simulate", "sb-arduino", "--analog", "A0=x"], "'x' is not a number of volts"),
        (["simulate", "sb-arduino", "--analog", "A0"], "'A0' is not PIN=VALUE"),
        (["simulate", "sb-arduino", "--digital", "1=1"], "'1' is not a pin an input can be held"),
        (["simulate", "sb-arduino", "--digital", "3=2"], "'2' is not a level: use 0 (low) or 1"),
    ],
)
def test_bad_kit_and_pin_options_say_what_is_allowed(
    arguments: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(arguments)
    assert exit_info.value.code == 2
    assert message in capsys.readouterr().err


def test_pin_options_are_refused_for_a_board_that_is_not_an_arduino(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["simulate", "sr-motor", "--digital", "3=1"]) == 2
    assert "apply to Arduino simulators only, not to SRMotorBoardFw3Simulator" in (
        capsys.readouterr().err
    )


@posix_only
def test_simulate_holds_analogue_and_digital_inputs_and_reports_the_serial() -> None:
    options = ("--time-scale", "0", "--serial", "RD77", "--analog", "a1=2.5", "--digital", "3=1")
    with simulating("sr-ruggeduino", *options, "--digital", "A2=0") as (process, path):
        with serial.Serial(path, 115200, timeout=5) as port:
            port.write(b"v")
            assert port.readline() == b"SRduino:1\n"
            port.write(b"ab")  # fw 1: analogue read of A1
            assert port.readline() == b"512\n"
            port.write(b"id")  # input on pin 3 ...
            port.readline()
            port.write(b"rd")  # ... read it: held high
            assert port.readline() == b"h\n"
        errors = stop(process, signal.SIGTERM)
    assert "(serial number RD77)" in errors


def test_simulate_help_lists_kits_on_demo(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["demo", "--help"])
    text = capsys.readouterr().out
    assert "default, sr2019, sb2019" in text
@pytest.mark.parametrize(
    ("argv0", "expected"),
    [
        ("/home/me/.venv/bin/j5aio", "j5aio"),
        ("C:\\venv\\Scripts\\j5aio.exe", "j5aio"),
        ("/src/j5aio/j5aio/__main__.py", "python -m j5aio"),
        ("-c", "python -m j5aio"),
        ("", "python -m j5aio"),
    ],
)
def test_the_usage_line_names_the_command_as_it_was_started(argv0: str, expected: str) -> None:
    from j5aio.__main__ import invoked_as

    assert invoked_as(argv0) == expected


def test_the_installed_command_shows_its_own_name(monkeypatch: pytest.MonkeyPatch) -> None:
    from j5aio.__main__ import build_parser

    monkeypatch.setattr(sys, "argv", ["/usr/local/bin/j5aio"])
    assert build_parser().format_usage().startswith("usage: j5aio ")
    monkeypatch.setattr(sys, "argv", ["/x/j5aio/__main__.py"])
    assert build_parser().format_usage().startswith("usage: python -m j5aio ")


TODAYS_KIT_PROGRAM = """
import anyio
from j5aio.kit import KitRobot

async def main():
    async with KitRobot() as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        await robot.servo_boards[0].servos[0].set_position(0.5)
        await robot.power_board.outputs[0].set_is_enabled(True)
        print("power", type(robot.power_board).__name__, robot.power_board.firmware_version)
        print("motor", type(robot.motor_boards[0]).__name__,
              robot.motor_boards[0].firmware_version)
        print("servo", type(robot.servo_boards[0]).__name__,
              len(robot.servo_boards[0].servos))

anyio.run(main)
"""


@pytest.mark.parametrize(
    ("kit", "expected"),
    [
        ("sr2023", ["power PowerBoardFw4 4.4.2", "motor MotorBoardFw4 4.4.1",
                    "servo ServoBoardFw4 12"]),
        ("sb2024", ["power PowerBoardFw4 4.4.2", "motor MotorBoardFw4 4.5.0",
                    "servo SBServoBoard 8"]),
    ],
)
def test_run_sim_runs_a_kit_robot_on_todays_kits_and_ends(
    tmp_path: Path, kit: str, expected: list[str]
) -> None:
    (tmp_path / "robot.py").write_text(TODAYS_KIT_PROGRAM)
    result = python_m_j5aio("run", "--sim", "--kit", kit, "robot.py", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[-3:] == expected


@pytest.mark.parametrize("kit", ["sr2023", "sb2024"])
def test_the_j5_program_keeps_running_on_todays_simulated_kits(kit: str) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", "--kit", kit,
         str(Path(__file__).resolve().parents[1] / "examples" / "console_j5_program.py")],
        input="true\n", capture_output=True, text=True, timeout=60, check=False,
        env={k: v for k, v in os.environ.items() if k not in (ENVIRONMENT_VARIABLE, "J5AIO_KIT")},
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("Found Power Board: SERIAL")
    assert "MotorBoard(SERIAL): Setting motor 0 to 0.5." in result.stdout


@pytest.mark.parametrize("kit", ["sr2019", "sb2019", "sr2023", "sb2024"])
def test_demo_on_each_kit_ends_by_itself(kit: str) -> None:
    result = python_m_j5aio("demo", "--kit", kit, "--seconds", "1")
    assert result.returncode == 0, result.stderr
    assert f"The kit: '{kit}'" in result.stdout
    assert result.stdout.rstrip().endswith("every simulated motor is braked.")


def test_a_reader_that_goes_away_ends_the_demo_quietly() -> None:
    root = Path(__file__).resolve().parents[1]
    path = os.pathsep.join([str(root), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    demo = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "demo"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
    )
    assert demo.stdout is not None and demo.stderr is not None
    assert demo.stdout.readline().startswith(b"j5aio demo")
    demo.stdout.close()  # as `j5aio demo | head -1` does
    try:
        status = demo.wait(timeout=60)
    finally:
        demo.kill()
    assert status == 1
    assert b"Traceback" not in demo.stderr.read()
    demo.stderr.close()


def test_only_broken_pipes_are_taken_for_a_reader_gone() -> None:
    from j5aio.__main__ import _only_broken_pipes

    assert _only_broken_pipes(BrokenPipeError())
    assert _only_broken_pipes(BaseExceptionGroup("g", [BrokenPipeError(), BrokenPipeError()]))
    assert not _only_broken_pipes(BaseExceptionGroup("g", [BrokenPipeError(), ValueError()]))


def test_any_other_error_group_from_a_command_is_not_swallowed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def failing(args: object) -> int:
        raise ExceptionGroup("boards", [ValueError("bad")])

    monkeypatch.setattr("j5aio.__main__._list", failing)
    with pytest.raises(ExceptionGroup):
        main(["list"])
