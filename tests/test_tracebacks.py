"""A student's traceback under ``python -m j5aio run``: their lines and the error, not ours."""

from __future__ import annotations

import io
import os
import re
import subprocess
import sys
from pathlib import Path

from j5aio.tracebacks import format_trimmed, is_ours, run_program

ROOT = Path(__file__).resolve().parents[1]

PROGRAM = """\
from j5aio.sync import KitRobot

robot = KitRobot()


def go() -> None:
    robot.motor_boards[0].motors[0].power = 1.5


go()
"""


def run(tmp_path: Path, **environ: str) -> subprocess.CompletedProcess[str]:
    program = tmp_path / "robot.py"
    program.write_text(PROGRAM, encoding="utf-8")
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", str(program)],
        capture_output=True, text=True, timeout=60, check=False,
        env={**os.environ, "PYTHONPATH": path, **environ},
    )


def test_the_traceback_shows_the_students_lines_and_the_error(tmp_path: Path) -> None:
    result = run(tmp_path)
    assert result.returncode == 1
    # after the run log's one line (j5aio run logs every run unless --no-log)
    err = result.stderr[result.stderr.index("Traceback"):]
    assert err.startswith("Traceback (most recent call last):\n")
    assert 'robot.py", line 10, in <module>' in err
    assert 'robot.py", line 7, in go' in err
    assert "ValueError: " in err
    assert "runpy" not in err
    assert "_runtime.py" not in err
    assert "_generated.py" not in err
    assert "J5AIO_FULL_TRACEBACK=1 to see them" in err
    assert len(err.splitlines()) < 12


def test_every_frame_on_request(tmp_path: Path) -> None:
    err = run(tmp_path, J5AIO_FULL_TRACEBACK="1").stderr
    assert "_runtime.py" in err
    assert "hidden" not in err


def _raise_chained() -> None:
    try:
        empty: dict[str, int] = {}
        empty["key"]
    except KeyError as error:
        raise RuntimeError("while looking up") from error


def test_causes_are_kept_and_trimmed_alike() -> None:
    try:
        _raise_chained()
    except RuntimeError as error:
        text = format_trimmed(error)
    assert "KeyError: 'key'" in text
    assert "The above exception was the direct cause" in text
    assert "RuntimeError: while looking up" in text
    assert "hidden" not in text  # all the frames here are the test's own


def test_which_frames_are_ours() -> None:
    import j5aio.sync._runtime as runtime

    assert is_ours(runtime.__file__)
    assert is_ours("<frozen runpy>")
    assert not is_ours(__file__)


def test_a_program_that_ends_well_returns_0(tmp_path: Path) -> None:
    program = tmp_path / "fine.py"
    program.write_text("print('fine')\n", encoding="utf-8")
    assert run_program(program) == 0


def test_a_failing_program_returns_1_and_prints_to_the_given_stream(tmp_path: Path) -> None:
    program = tmp_path / "bad.py"
    program.write_text("raise LookupError('nope')\n", encoding="utf-8")
    out = io.StringIO()
    assert run_program(program, stderr=out) == 1
    lines = out.getvalue().rstrip().splitlines()
    assert lines[-2] == "LookupError: nope"
    assert re.fullmatch(r"\(\d+ frames inside j5aio hidden; set J5AIO_FULL_TRACE.*", lines[-1])
    assert 'bad.py", line 1, in <module>' in lines[1]


def test_the_members_of_an_exception_group_are_trimmed_too(tmp_path: Path) -> None:
    program = tmp_path / "group.py"
    program.write_text(
        "raise ExceptionGroup('two', [ValueError('one'), KeyError('other')])\n",
        encoding="utf-8",
    )
    out = io.StringIO()
    assert run_program(program, stderr=out) == 1
    text = out.getvalue()
    assert "ExceptionGroup: two (2 sub-exceptions)" in text
    assert "ValueError: one" in text and "KeyError: 'other'" in text
    assert "runpy" not in text


# -- "Did you mean": Python 3.12 prints it itself; on 3.11 j5aio adds it -------------------


class _Piezo:
    def buzz(self) -> None: ...


def _raised(code: str, scope: dict[str, object]) -> BaseException:
    try:
        exec(code, scope)
    except Exception as error:
        return error
    raise AssertionError("no error")  # pragma: no cover


def test_a_misspelt_attribute_gets_the_name_it_meant() -> None:
    from j5aio.tracebacks import suggestion

    error = _raised("piezo.buz()", {"piezo": _Piezo()})
    assert suggestion(error) == "buzz"
    assert "no attribute 'buz'. Did you mean: 'buzz'?" in format_trimmed(error)


def test_a_misspelt_name_gets_the_name_it_meant() -> None:
    from j5aio.tracebacks import suggestion

    error = _raised("motor_power = 1\nprint(motor_powr)", {})
    assert suggestion(error) == "motor_power"
    assert suggestion(_raised("prnt(1)", {})) == "print"


def test_nothing_is_suggested_for_a_name_far_from_every_other() -> None:
    from j5aio.tracebacks import suggestion

    assert suggestion(_raised("piezo.sing()", {"piezo": _Piezo()})) is None
    assert suggestion(_raised("xyzzy_plugh", {})) is None
    assert suggestion(ValueError("no name here")) is None
    # a private name is offered only for a private name
    assert suggestion(_raised("piezo.dict__", {"piezo": _Piezo()})) is None


def test_an_object_whose_dir_fails_gets_no_hint() -> None:
    from j5aio.tracebacks import suggestion

    class Broken:
        def __dir__(self) -> list[str]:
            raise RuntimeError("no listing")

    assert suggestion(_raised("thing.nme", {"thing": Broken()})) is None


def test_the_hint_appears_under_j5aio_run_as_under_plain_python(tmp_path: Path) -> None:
    program = tmp_path / "robot.py"
    program.write_text(
        "from j5aio.sync import KitRobot\nrobot = KitRobot()\nrobot.power_board.piezo.buz(1, 2)\n",
        encoding="utf-8",
    )
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    for full in ("", "1"):
        result = subprocess.run(
            [sys.executable, "-m", "j5aio", "run", "--sim", "--no-log", str(program)],
            capture_output=True, text=True, timeout=60, check=False,
            env={**os.environ, "PYTHONPATH": path, "J5AIO_FULL_TRACEBACK": full},
        )
        assert result.stderr.count("Did you mean: 'buzz'?") == 1, result.stderr
