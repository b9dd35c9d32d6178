"""Starting the view: the command line, KitRobot(view=...), and without the view extra."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from j5aio.__main__ import main

ROOT = Path(__file__).resolve().parents[2]

# A meta-path finder that makes the web stack look uninstalled, for a child Python.
BLOCK_AIOHTTP = textwrap.dedent(
    """
    import sys
    class _NoAiohttp:
        def find_spec(self, name, path=None, target=None):
            if name == "aiohttp" or name.startswith("aiohttp."):
                raise ModuleNotFoundError(f"No module named {name!r}")
            return None
    sys.meta_path.insert(0, _NoAiohttp())
    """
)

PROGRAM = textwrap.dedent(
    """
    import anyio
    from j5aio.kit import KitRobot

    async def main():
        async with KitRobot() as robot:
            await robot.motor_boards[0].motors[0].set_power(0.5)
            print("program ran", flush=True)

    anyio.run(main)
    """
)


def run_python(
    code: str, *arguments: str, cwd: Path | None = None
) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("J5AIO_VIEW", None)
    return subprocess.run(
        [sys.executable, "-c", code, *arguments],
        capture_output=True,
        text=True,
        timeout=60,
        env=env,
        cwd=cwd,
    )


def test_import_j5aio_never_imports_the_web_stack() -> None:
    result = run_python(
        "import sys, j5aio, j5aio.kit, j5aio.view, j5aio.demo, j5aio.__main__\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('aiohttp', 'selenium')))"
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"


def test_without_the_extra_the_view_says_what_to_install(tmp_path: Path) -> None:
    code = BLOCK_AIOHTTP + textwrap.dedent(
        """
        import anyio
        from j5aio.view import ViewNotInstalledError, start_view

        async def main():
            try:
                start_view()
            except ViewNotInstalledError as error:
                print("refused:", error)

        anyio.run(main)
        """
    )
    result = run_python(code)
    assert result.returncode == 0, result.stderr
    assert "refused:" in result.stdout and "pip install 'j5aio[view]'" in result.stdout

    program = tmp_path / "robot.py"
    program.write_text(PROGRAM)
    cli = (
        BLOCK_AIOHTTP + "import sys\nfrom j5aio.__main__ import main\nsys.exit(main(sys.argv[1:]))"
    )
    result = run_python(cli, "run", "--sim", "--view", str(program))
    assert result.returncode == 2
    assert "pip install 'j5aio[view]'" in result.stderr
    assert "program ran" not in result.stdout


def test_run_sim_view_prints_one_view_line(tmp_path: Path) -> None:
    pytest.importorskip("aiohttp", reason="the view extra is not installed")
    program = tmp_path / "robot.py"
    program.write_text(PROGRAM)
    cli = "import sys\nfrom j5aio.__main__ import main\nsys.exit(main(sys.argv[1:]))"
    result = run_python(cli, "run", "--sim", "--view", "--view-port", "0", str(program))
    assert result.returncode == 0, result.stderr
    view_lines = [line for line in result.stdout.splitlines() if line.startswith("View: ")]
    assert len(view_lines) == 1
    assert view_lines[0].startswith("View: http://127.0.0.1:") and "/?token=" in view_lines[0]
    assert "program ran" in result.stdout
    assert "WARNING" not in result.stderr


def test_view_options_are_checked(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    program = tmp_path / "robot.py"
    program.write_text("")
    assert main(["run", "--view-port", "8000", str(program)]) == 2
    assert "need --view" in capsys.readouterr().err
    assert main(["demo", "--view-host", "0.0.0.0"]) == 2
    for bad in ("http", "70000", "-1", "1.5"):
        with pytest.raises(SystemExit):
            main(["run", "--view", "--view-port", bad, str(program)])
        assert "port number" in capsys.readouterr().err


SYNC_PROGRAM = textwrap.dedent(
    """
    import time
    from j5aio.boards.sr.v4 import MotorBoard
    from j5aio.simulator.environment import SRV4MotorBoardSimulatedBackend
    from j5aio.simulator.kit import KitConfig, use_kit
    from j5aio.sync import BoardGroup
    from j5aio.sync._runtime import get_loop
    from j5aio.view import current_view

    kit = use_kit(KitConfig(motor_boards=1))
    board = BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardSimulatedBackend).singular()
    board.motors[0].power = 0.5
    view = current_view()
    assert ("SIMMB0:motor:0", "motor_state", 0.5) in view.state.changes(0, 0).values
    assert view.state.loop is get_loop()  # the portal's (run by its callers or its keeper)
    SEEN.append(view.url)
    """
)


def test_run_view_shows_a_sync_program_too(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    pytest.importorskip("aiohttp", reason="the view extra is not installed")
    from j5aio.view import current_view

    program = tmp_path / "sync_robot.py"
    program.write_text("from builtins import SEEN\n" + SYNC_PROGRAM)
    seen: list[str] = []
    monkeypatch.setattr("builtins.SEEN", seen, raising=False)
    monkeypatch.setattr(sys, "argv", list(sys.argv))
    monkeypatch.setattr(sys, "path", list(sys.path))
    from j5aio.sync import shutdown

    try:
        assert main(["run", "--view", str(program)]) == 0
    finally:
        shutdown()  # the sync portal's boards made safe and closed
    out = capsys.readouterr().out
    assert seen and out.startswith(f"View: {seen[0]}")
    assert current_view() is None  # closed when the program ended


def test_demo_view_runs_longer_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("aiohttp", reason="the view extra is not installed")
    monkeypatch.setenv("J5AIO_VIEW", "")
    monkeypatch.delenv("J5AIO_VIEW")
    seen: list[float] = []

    def fake_demo(seconds: float, kit: str | None = None) -> bool:
        seen.append(seconds)
        return True

    monkeypatch.setattr("j5aio.demo.run_demo", fake_demo)
    assert main(["demo", "--view"]) == 0
    assert main(["demo", "--view", "--seconds", "2"]) == 0
    assert seen == [120.0, 2.0]
