"""The Bee Board's generated sync facade: it works, it is typed, and CI notices it going stale."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import textwrap
import uuid
from pathlib import Path

import beekit.sync
import pytest
from bee_robot import main
from beekit.backend import BeeBackend
from beekit.simulator import BeeSimulator
from mypy import api

from j5aio import sync, syncgen
from j5aio.simulator.kit import current_kit, use_kit
from j5aio.testing.plugin import PtySimulatorFactory

KIT_ROOT = Path(__file__).resolve().parent
REPO_ROOT = KIT_ROOT.parents[1]
SYNC_MODULE = KIT_ROOT / "beekit" / "sync.py"


WORKER = os.environ.get("PYTEST_XDIST_WORKER", "main")


def test_a_student_program_drives_the_board_on_the_simulated_kit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("J5AIO_ENV", "sim")  # as ``run --sim`` sets it
    previous = current_kit()
    kit = use_kit("bee")
    simulator = kit.simulators("bee")[0]
    assert isinstance(simulator, BeeSimulator)
    simulator.button_held = True  # the student has pressed the button already
    try:
        bee = main()  # the environment J5AIO_ENV chooses: the program names no backend
        try:
            assert isinstance(bee, beekit.sync.BeeBoard)
            assert isinstance(bee.motors[0], sync.Motor)
            assert bee.motors[0].power == 0.5
            assert simulator.led is True
            assert simulator.motor_steps == [50, 50]
        finally:
            bee.close()
    finally:
        use_kit(previous)


def test_a_student_program_runs_on_the_console() -> None:
    environment = {
        # this run's own robot lock port is kept, so that the program runs beside a robot
        **{
            k: v for k, v in os.environ.items()
            if not k.startswith("J5AIO_") or k == "J5AIO_LOCK_PORT"
        },
        "J5AIO_ENV": "console",
        "PYTHONPATH": os.pathsep.join([str(REPO_ROOT), str(KIT_ROOT)]),
    }
    result = subprocess.run(
        [sys.executable, str(KIT_ROOT / "bee_robot.py")], input="\n", capture_output=True,
        text=True, timeout=60, env=environment, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "LED on" in result.stdout
    assert "Hit return to press the button" in result.stdout
    assert "Motor 1 power set to 0.5" in result.stdout


def test_the_core_board_class_gives_the_kits_wrapper_too(
    j5aio_pty_simulator: PtySimulatorFactory,
) -> None:
    from beekit.boards import BeeBoard as CoreBeeBoard

    path = j5aio_pty_simulator(BeeSimulator())
    bee = sync.BoardGroup.get_board_group(CoreBeeBoard, BeeBackend, ports=[path]).singular()
    assert type(bee) is beekit.sync.BeeBoard
    bee.close()


GOOD = """
from beekit.backend import BeeBackend
from beekit.sync import BeeBoard
from j5aio.sync import BoardGroup

bee = BoardGroup.get_board_group(BeeBoard, BeeBackend).singular()
reveal_type(bee)
reveal_type(bee.motors[0])
reveal_type(bee.led.state)
bee.motors[1].power = -0.25
bee.button.wait_until_pressed(timeout=2.0)
"""

BAD = """
from beekit.backend import BeeBackend
from beekit.sync import BeeBoard
from j5aio.sync import BoardGroup

bee = BoardGroup.get_board_group(BeeBoard, BeeBackend).singular()
bee.moters[0].power = 0.5
bee.led.state = "on"
"""


def test_the_generated_module_is_typed(tmp_path: Path) -> None:
    files = {}
    for name, source in (("good", GOOD), ("bad", BAD)):
        path = tmp_path / f"bee_{name}_{uuid.uuid4().hex}.py"
        path.write_text(textwrap.dedent(source), encoding="utf-8")
        files[name] = path
    stdout, stderr, _ = api.run(
        [
            "--strict",
            "--no-error-summary",
            "--cache-dir",
            # one cache per pytest-xdist worker: two mypy runs never share one
            str(Path(tempfile.gettempdir()) / f"j5aio-beekit-mypy-cache-{WORKER}"),
            "--config-file",
            str(REPO_ROOT / "pyproject.toml"),
            *map(str, files.values()),
        ],
    )
    assert not stderr, stderr
    good = [line for line in stdout.splitlines() if line.startswith(str(files["good"]))]
    bad = [line for line in stdout.splitlines() if line.startswith(str(files["bad"]))]
    assert [line for line in good if ": error:" in line] == []
    revealed = [line.split("Revealed type is ")[1] for line in good if "Revealed type" in line]
    motor = '"j5aio.sync._generated.components.Motor"'
    assert revealed == ['"beekit.sync.BeeBoard"', motor, '"bool"']
    errors = [line for line in bad if ": error:" in line]
    assert len(errors) == 2, errors
    assert '"BeeBoard" has no attribute "moters"' in errors[0]
    assert "[assignment]" in errors[1]


def test_the_committed_sync_module_is_fresh() -> None:
    assert SYNC_MODULE.read_text(encoding="utf-8") == syncgen.generate(["beekit.boards"])


def test_the_generated_module_imports_only_public_names_of_j5aio() -> None:
    imports = [
        line for line in SYNC_MODULE.read_text(encoding="utf-8").splitlines()
        if line.startswith(("import ", "from "))
    ]
    j5aio_modules = [line.split()[1] for line in imports if line.split()[1].startswith("j5aio")]
    assert j5aio_modules
    for module in j5aio_modules:
        assert not any(part.startswith("_") for part in module.split(".")), module
    assert "j5aio.sync.wrapping" in j5aio_modules


def test_walking_the_whole_package_finds_only_the_board() -> None:
    assert syncgen.discover(syncgen.Scope(modules=("beekit",))).classes == [
        sys.modules["beekit.boards"].BeeBoard,
    ]


def test_check_finds_a_stale_module(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "sync.py"
    target.write_text(
        SYNC_MODULE.read_text(encoding="utf-8").replace("The LED.", "The old LED."),
        encoding="utf-8",
    )
    args = ["beekit.boards", "-o", str(target)]
    assert syncgen.main([*args, "--check"]) == 1
    assert "is stale: run python -m j5aio sync-gen beekit.boards -o" in capsys.readouterr().err
    assert syncgen.main(args) == 0
    assert syncgen.main([*args, "--check"]) == 0
    assert target.read_text(encoding="utf-8") == SYNC_MODULE.read_text(encoding="utf-8")


def test_the_command_line_checks_the_committed_module() -> None:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO_ROOT), str(KIT_ROOT)])}
    command = [sys.executable, "-m", "j5aio", "sync-gen", "beekit.boards", "-o"]
    fresh = subprocess.run(
        [*command, str(SYNC_MODULE), "--check"],
        env=env, capture_output=True, text=True, check=False, timeout=120,
    )
    assert fresh.returncode == 0, fresh.stderr
    missing = subprocess.run(
        [*command, str(SYNC_MODULE.with_name("nowhere.py")), "--check"],
        env=env, capture_output=True, text=True, check=False, timeout=120,
    )
    assert missing.returncode == 1
    assert "is stale" in missing.stderr


def test_sync_gen_refuses_a_module_without_boards(capsys: pytest.CaptureFixture[str]) -> None:
    assert syncgen.main(["beekit.backend_missing", "-o", "unused.py"]) == 2
    assert "No module named" in capsys.readouterr().err
    assert syncgen.main(["beekit.simulator", "-o", "unused.py", "--check"]) == 2
    assert "found no board or component classes" in capsys.readouterr().err
