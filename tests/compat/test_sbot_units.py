"""The parts of ``j5aio.compat.sbot`` that need no robot: conversions, overrides, numbering."""

from __future__ import annotations

import logging
import math
import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

# As in sbot's own tests: with SBOT_PYTEST set, importing the package finds no boards.
os.environ["SBOT_PYTEST"] = "1"

from j5aio.compat.sbot import _logging, _overrides
from j5aio.compat.sbot._checks import float_bounds_check, map_to_float, map_to_int
from j5aio.compat.sbot._kit import NOT_LOADED, KitLink, _sorted_boards
from j5aio.compat.sbot._leds import Colour, Led
from j5aio.compat.sbot._vision import Vision
from j5aio.compat.sbot.internal.exceptions import (
    BoardDisconnectionError,
    MetadataKeyError,
    MetadataNotReadyError,
)
from j5aio.compat.sbot.marker import Marker
from j5aio.errors import CommunicationError
from j5aio.vision import markers as core

from .test_sbot_programs import ROOT, run_sbot_program


def test_numbers_reach_the_boards_as_sbot_computes_them() -> None:
    assert map_to_int(0.5, -1.0, 1.0, -1000, 1000) == 500
    assert map_to_int(-0.0015, -1.0, 1.0, -1000, 1000) == -1  # truncated, not rounded
    assert map_to_int(0.5, -1.0, 1.0, 350, 1980) == 1572
    assert map_to_float(1570, 350, 1980, -1.0, 1.0) == 0.497
    assert float_bounds_check("0.25", -1, 1, "msg") == 0.25
    with pytest.raises(TypeError, match=r"^msg$"):
        float_bounds_check("fast", -1, 1, "msg")
    with pytest.raises(TypeError, match=r"^msg$"):
        float_bounds_check(None, -1, 1, "msg")
    for bad in (1.5, math.nan):
        with pytest.raises(ValueError, match=r"^msg$"):
            float_bounds_check(bad, -1, 1, "msg")


def test_the_override_file_is_read_as_python_dotenv_reads_it(tmp_path: Path) -> None:
    text = (
        "# a comment\n\nskip_wait_start=1\nexport SORT_MOTOR_ORDER = 'MB2,MB1'\n"
        'ENABLE_DEBUG_LOGGING="0"\nNO_VALUE\n=x\nMANUAL_MOTOR_PORTS=/dev/a # note\n'
    )
    assert _overrides.parse_env_file(text) == {
        "SKIP_WAIT_START": "1",
        "SORT_MOTOR_ORDER": "MB2,MB1",
        "ENABLE_DEBUG_LOGGING": "0",
        "NO_VALUE": None,
        "MANUAL_MOTOR_PORTS": "/dev/a",
    }


def test_the_file_wins_over_the_environment(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("SBOT_SKIP_WAIT_START", "0")
    monkeypatch.setenv("SBOT_ENABLE_TRACE_LOGGING", "1")
    (tmp_path / _overrides.OVERRIDE_FILE).write_text("SKIP_WAIT_START=1\n")
    try:
        found = _overrides.load_overrides(tmp_path)
        assert found["SKIP_WAIT_START"] == "1"
        assert _overrides.is_set("SKIP_WAIT_START") and _overrides.is_set("ENABLE_TRACE_LOGGING")
        assert not _overrides.is_set("ENABLE_DEBUG_LOGGING")
        assert _overrides.get_overrides() is found
        (tmp_path / _overrides.OVERRIDE_FILE).write_bytes(b"\xff\xfe")  # not UTF-8: ignored
        assert _overrides.load_overrides(tmp_path)["SKIP_WAIT_START"] == "0"
    finally:
        monkeypatch.undo()
        _overrides.load_overrides()


def test_boards_are_numbered_by_serial_or_by_the_order_given() -> None:
    boards = [SimpleNamespace(serial_number=s) for s in ("MB2", "MB1", "MB3")]
    assert [b.serial_number for b in _sorted_boards(boards, None, "motor")] == [
        "MB1", "MB2", "MB3",
    ]
    ordered = _sorted_boards(boards, "MB3,MB1,MB2,MB9", "motor")
    assert [b.serial_number for b in ordered] == ["MB3", "MB1", "MB2"]
    with pytest.raises(RuntimeError, match="Extra boards found for motor: MB2"):
        _sorted_boards(boards, "MB3,MB1", "motor")


def test_nothing_is_reached_before_the_boards_are_loaded() -> None:
    link = KitLink()
    assert not link.loaded
    for call in (lambda: link.robot, lambda: link.motor(0), link.arduino):
        with pytest.raises(AssertionError, match=r"utils\.load_boards"):
            call()
    assert NOT_LOADED.startswith("Boards cannot be accessed")
    led = Led(link)
    led.set_colour(0, Colour.RED)  # no HAT known: nothing lights, as sbot off the Pi
    assert led.get_colour(0) is Colour.OFF


def test_an_output_number_must_be_an_int() -> None:
    link = KitLink()
    link._robot = object()  # type: ignore[assignment]
    with pytest.raises(TypeError, match="an int from 0"):
        link.motor("0")  # type: ignore[arg-type]


def test_vision_without_a_camera_says_so() -> None:
    boards: Any = SimpleNamespace(robot=SimpleNamespace(camera=None))
    with pytest.raises(ValueError, match="No cameras connected"):
        Vision(boards).capture()


def test_a_marker_without_a_pose_is_refused_as_sbot_does() -> None:
    centre = core.PixelCoordinates(1.0, 2.0)
    seen = core.Marker(3, 100.0, centre, (centre, centre, centre, centre))
    with pytest.raises(ValueError, match="lacks pose"):
        Marker.from_core(seen)
    posed = seen._replace(
        position=core.Position(1234.9, 0.5, -0.25), orientation=core.Orientation(1, 2, 3),
    )
    marker = Marker.from_core(posed)
    assert marker.position.distance == 1234 and marker.size == 100
    assert marker.orientation.roll == 3
    assert type(marker.pixel_centre).__module__ == "j5aio.compat.sbot.marker"


def test_the_exceptions_keep_sbots_base_classes() -> None:
    assert issubclass(MetadataNotReadyError, RuntimeError)
    assert issubclass(MetadataKeyError, KeyError)
    assert str(MetadataKeyError("zone")) == "Key 'zone' not present in metadata"
    assert issubclass(BoardDisconnectionError, OSError)
    assert issubclass(BoardDisconnectionError, CommunicationError)


def test_logging_is_set_up_as_sbot_does(monkeypatch: pytest.MonkeyPatch) -> None:
    root = logging.getLogger()
    monkeypatch.setattr(root, "handlers", [])
    monkeypatch.setattr(root, "level", root.level)
    _logging.setup_logging(debug_logging=True, trace_logging=False)
    assert root.level == logging.DEBUG and len(root.handlers) == 1
    _logging.setup_logging(debug_logging=False, trace_logging=True)
    assert root.level == _logging.TRACE and len(root.handlers) == 1
    assert logging.getLevelName(_logging.TRACE) == "TRACE"
    _logging.setup_logging(debug_logging=False, trace_logging=False)
    assert root.level == logging.INFO


def test_sbot_pytest_imports_the_names_without_a_robot() -> None:
    environment = {**os.environ, "SBOT_PYTEST": "1", "PYTHONPATH": str(ROOT)}
    result = subprocess.run(
        [
            sys.executable, "-c",
            "import j5aio.compat.sbot as sbot, sys\n"
            "print(sbot.BRAKE == 0, sbot.COAST == -1024, hasattr(sbot, 'motors'),\n"
            "      'j5aio.compat.sbot._robot' in sys.modules, 'j5aio.kit' in sys.modules)\n",
        ],
        capture_output=True, text=True, timeout=60, env=environment, cwd=ROOT, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["True", "True", "False", "False", "False"]


def test_the_robot_is_made_when_a_program_first_takes_its_modules() -> None:
    environment = {
        **{k: v for k, v in os.environ.items() if not k.startswith("SBOT_")},
        "SBOT_SKIP_WAIT_START": "1",
        "PYTHONPATH": str(ROOT),
    }
    result = subprocess.run(
        [
            sys.executable, "-c",
            "import sys\n"
            "import j5aio.compat.sbot as sbot\n"
            "from j5aio.compat.sbot import marker, game_specific\n"
            "print('_robot' in dir(sbot), 'j5aio.compat.sbot._robot' in sys.modules)\n"
            "from j5aio.compat.sbot import motors, utils\n"
            "print('j5aio.compat.sbot._robot' in sys.modules, sbot.utils is utils)\n"
            "try:\n"
            "    sbot.motor\n"
            "except AttributeError as error:\n"
            "    print(error)\n",
        ],
        capture_output=True, text=True, timeout=60, env=environment, cwd=ROOT, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "sbot.robot - INFO - SourceBots API v2026.1.0" in result.stdout
    assert [line for line in result.stdout.splitlines() if " - INFO - " not in line] == [
        "False False",
        "True True",
        "module 'j5aio.compat.sbot' has no attribute 'motor'",
    ]


def test_the_leds_light_the_hat_and_a_missing_arduino_is_named() -> None:
    process, got, _ = run_sbot_program(
        "sbot_hat.py", kit="sr2023", env={"SBOT_HARNESS_BENCH": "0"},
    )
    assert process.returncode == 0, process.stderr[-3000:]
    assert got["colours"] == ["CYAN", "OFF", "YELLOW"]
    assert got["no_arduino"] == "No Arduinos connected"
    assert got["repr"] == "<Arduino no arduino connected>"


def test_status_replies_parse_as_sbot_parses_them() -> None:
    from j5aio.compat.sbot._motors import MotorStatus
    from j5aio.compat.sbot._power import PowerStatus
    from j5aio.compat.sbot._servos import ServoStatus
    from j5aio.compat.sbot.internal.exceptions import IncorrectBoardError

    assert MotorStatus.from_status_response("0,1:12250") == ((False, True), 12.25, [])
    assert PowerStatus.from_status_response("0,0,1,0,0,0,0:31:1:5012:x") == (
        (False, False, True, False, False, False, False), 31, True, 5.012, ["x"],
    )
    assert ServoStatus.from_status_response("1:0") == (True, False)
    error = IncorrectBoardError("MCv4B", "PBv4B")
    assert isinstance(error, OSError)
    assert str(error) == "Board returned type 'MCv4B', expected 'PBv4B'"


class _FakePin:
    """A facade pin whose board has forgotten what it was told (it rebooted)."""

    def __init__(self) -> None:
        from j5aio.components.gpio_pin import GPIOPinMode as Core

        self.mode = Core.DIGITAL_INPUT
        self.reads = 0

    @property
    def last_digital_write(self) -> bool:
        from j5aio.components.gpio_pin import GPIOPinMode as Core
        from j5aio.errors import BadGPIOPinModeError

        if self.mode is not Core.DIGITAL_OUTPUT:
            raise BadGPIOPinModeError("not an output")
        return True

    def digital_read(self) -> bool:
        from j5aio.components.gpio_pin import GPIOPinMode as Core
        from j5aio.errors import BadGPIOPinModeError

        if self.mode not in (Core.DIGITAL_INPUT, Core.DIGITAL_INPUT_PULLUP):
            raise BadGPIOPinModeError("not a digital input")
        self.reads += 1
        return True

    def analogue_read(self) -> float:
        from j5aio.components.gpio_pin import GPIOPinMode as Core
        from j5aio.errors import BadGPIOPinModeError

        if self.mode is not Core.ANALOGUE_INPUT:
            raise BadGPIOPinModeError("not an analogue input")
        return 2.5


def test_a_pin_mode_the_board_forgot_is_read_again() -> None:
    from j5aio.compat.sbot._arduinos import Arduino, GPIOPinMode
    from j5aio.components.gpio_pin import GPIOPinMode as Core

    pin, analogue = _FakePin(), _FakePin()
    board = SimpleNamespace(pins={3: pin, 14: analogue}, serial_number="AR1")
    boards: Any = SimpleNamespace(arduino=lambda: board, arduinos=[board])
    arduino = Arduino(boards)
    arduino.set_pin_mode(3, GPIOPinMode.OUTPUT)
    assert arduino.digital_read(3) is True  # the output's last level
    pin.mode = Core.DIGITAL_INPUT  # the board rebooted: every pin an input
    assert arduino.digital_read(3) is True
    assert pin.reads == 1  # read from the board once the mode was known again
    pin.mode = Core.DIGITAL_OUTPUT  # (behind the module's back again)
    assert arduino.digital_read(3) is True  # now the output's last level
    arduino.set_pin_mode(14, GPIOPinMode.INPUT)
    assert arduino.analog_read(14) == 2.502  # 2.5 V is 512 of 1023 steps
    analogue.mode = Core.DIGITAL_INPUT  # the board rebooted
    assert arduino.analog_read(14) == 2.502  # the pin is made an analogue input again
    assert analogue.mode is Core.ANALOGUE_INPUT
    assert repr(arduino) == "<Arduino AR1>"


class _UnpluggedMotor:
    @property
    def current(self) -> float:
        from j5aio.errors import CommunicationTimeoutError

        raise CommunicationTimeoutError("the motor board did not answer")


def test_a_board_that_stops_answering_is_sbots_disconnection_error() -> None:
    from j5aio.compat.sbot import _errors
    from j5aio.compat.sbot._motors import Motor

    output = SimpleNamespace(component=_UnpluggedMotor())
    boards: Any = SimpleNamespace(motor=lambda id: output)
    motors = Motor(boards)
    with pytest.raises(OSError, match="did not answer") as caught:
        motors.get_motor_current(0)
    assert isinstance(caught.value, BoardDisconnectionError)
    assert isinstance(caught.value.__cause__, CommunicationError)
    assert motors.get_motor_current.__name__ == "get_motor_current"
    timer: Any = SimpleNamespace(ended_at=None)
    _errors._timers.append(timer)
    try:
        timer.ended_at = 1.0  # the match is over: the program ends quietly
        with pytest.raises(SystemExit) as ended:
            motors.get_motor_current(0)
        assert ended.value.code == 0
        assert _errors._game_over.is_set()
        _errors.end_of_match()  # (once only)
    finally:
        _errors._timers.remove(timer)
        _errors._game_over.clear()
