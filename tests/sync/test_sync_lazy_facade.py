"""j5aio's facade imports no core module its definitions do not need."""

from __future__ import annotations

import enum
import math
import subprocess
import sys

import pytest

from j5aio.sync import wrapping
from j5aio.syncgen._class_writer import _is_plain_literal

from .sync_fakes import ROOT, child_env

#: Core modules of boards and components that a program of one kit may never use.
NOT_NEEDED_TO_START = (
    "j5aio.kit",
    "j5aio.boards.sr.kch",
    "j5aio.boards.sb.servo_board",
    "j5aio.boards.sr.v4.power_board_fw4",
    "j5aio.components.fan",
    "j5aio.components.rgb_led",
    "j5aio.vision.track",
)


def _run(source: str) -> str:
    result = subprocess.run(
        [sys.executable, "-c", source],
        capture_output=True, text=True, timeout=60, cwd=ROOT, env=child_env(), check=False,
    )
    assert result.returncode == 0, result.stderr
    return result.stdout.strip()


def test_importing_the_facade_imports_no_board_module() -> None:
    loaded = _run(
        "import sys\n"
        "from j5aio.sync import KitRobot, PowerBoard, Fan, Colour\n"
        f"print(sorted(m for m in {NOT_NEEDED_TO_START!r} if m in sys.modules))\n"
    )
    assert loaded == "[]"


def test_a_wrapper_class_asked_for_its_core_class_imports_that_class_alone() -> None:
    loaded = _run(
        "import sys\n"
        "from j5aio.sync import Fan, wrapping\n"
        "from j5aio.components.fan import Fan as CoreFan\n"
        "assert wrapping.unwrap(Fan) is CoreFan\n"
        "print(sorted(m for m in ('j5aio.boards.sr.kch', 'j5aio.components.rgb_led')"
        " if m in sys.modules))\n"
    )
    assert loaded == "[]"


def test_the_facades_written_out_constants_equal_the_cores() -> None:
    checked = 0
    for core, wrapper in wrapping.registered().items():
        for name, value in vars(wrapper).items():
            if not name.startswith("_") and _is_plain_literal(value) and hasattr(core, name):
                assert getattr(core, name) == value, f"{wrapper.__name__}.{name}"
                checked += 1
    assert checked > 20


class Level(enum.IntEnum):
    LOW = 1


@pytest.mark.parametrize(
    ("value", "plain"),
    [
        (1, True),
        (True, True),
        (1.5, True),
        ("Power Board", True),
        (None, True),
        (range(2, 14), True),
        ((0.0, (1, "x")), True),
        (math.inf, False),
        (math.nan, False),
        (Level.LOW, False),  # an int, but its repr is not source
        (frozenset({1}), False),
        ([1, 2], False),
        ((1, [2]), False),
        (int, False),
    ],
)
def test_a_plain_literal_is_one_whose_repr_is_its_source(value: object, plain: bool) -> None:
    assert _is_plain_literal(value) is plain
    if plain:
        assert eval(repr(value)) == value


def _families(names: str) -> str:
    """Source printing which of the facade's family modules are imported."""
    return (
        "print(sorted(m.rpartition('.')[2] for m in sys.modules"
        f" if m.startswith('j5aio.sync._generated.')), {names})\n"
    )


def test_a_robot_imports_the_wrappers_of_what_the_program_uses() -> None:
    loaded = _run(
        "import os, sys\n"
        "os.environ['J5AIO_ENV'] = 'sim'\n"
        "from j5aio.sync import KitRobot\n"
        "robot = KitRobot()\n"
        + _families("'ready'")
        + "board = robot.motor_boards[0]\n"
        + _families("type(board).__name__")
        + "motor = board.motors[0]\n"
        + _families("type(motor).__name__")
    )
    ready, board, motor = loaded.splitlines()
    assert ready == "['robot'] ready"
    assert board == "['arduino', 'components', 'robot', 'sr'] MotorBoard"
    assert motor == "['arduino', 'components', 'robot', 'sr'] Motor"


def test_wrapping_an_object_imports_the_module_of_its_wrapper() -> None:
    loaded = _run(
        "import sys\n"
        "from j5aio.sync import wrapping, _generated\n"
        "from j5aio.components.motor import Motor\n"
        "motor = Motor.__new__(Motor)\n"
        + _families("'before'")
        + "face = wrapping.wrap(motor)\n"
        + _families("type(face).__module__")
        + "wrapping.registered()\n"
        + _families("'all'")
    )
    before, after, everything = loaded.splitlines()
    assert before == "[] before"
    assert after == "['components', 'robot'] j5aio.sync._generated.components"
    assert everything == (
        "['arduino', 'components', 'environment', 'fw4', 'robot', 'sb', 'sr', 'vision'] all"
    )


def test_a_class_without_a_wrapper_module_is_left_as_it_is() -> None:
    class Plain:
        pass

    assert wrapping.wrap(plain := Plain()) is plain


def test_the_component_wrappers_load_no_module_their_annotations_alone_name() -> None:
    # ``timedelta`` is named by the piezo's and the ultrasound sensor's annotations only:
    # the wrappers load neither it nor the C module it comes from. (What the interpreter's
    # start loaded is left out: under tox, coverage's start-up hook imports datetime.)
    loaded = _run(
        "import sys\n"
        "before = set(sys.modules)\n"
        "from j5aio.sync import Piezo, UltrasoundSensor\n"
        "print(sorted(m for m in ('_datetime', 'datetime', 'j5aio._timedelta')"
        " if m in sys.modules and m not in before))\n"
    )
    assert loaded == "[]"


def test_only_names_read_outside_annotations_are_read_at_run_time() -> None:
    from j5aio.syncgen._module_writer import _names_read_at_run_time

    source = (
        "class Wrapper(Base):\n"
        "    LIMIT: ClassVar[Span] = Default.LIMIT\n"
        "    def play(self, duration: Span | int = NONE, *more: Extra, **kw: Keyed) -> Result:\n"
        "        value: Local = convert(duration)\n"
        "        return cast('Result', value)\n"
    )
    assert _names_read_at_run_time([source]) == {
        "Base", "Default", "NONE", "convert", "cast", "value", "duration",
    }
