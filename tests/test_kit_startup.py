"""What a robot on the simulated kit loads at start-up: nothing it does not use.

Each program runs in a fresh interpreter, so that what it imported is its own; the
modules a bare ``anyio.run`` loads (the interpreter's site packages, say) are left out
of the comparison.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

REPORT = (
    "import sys\n"
    "_loaded = sorted(sys.modules)\n"
    "import json\n"
    "print('MODULES', json.dumps(_loaded))\n"
)

#: What every program here runs first: it forgets datetime, which the interpreter's start
#: may have loaded (coverage's subprocess hook does), so that what is counted is whether
#: the program itself brings it back.
FORGET_DATETIME = (
    "import sys\nfor _name in ('datetime', '_datetime'):\n    sys.modules.pop(_name, None)\n"
)

BARE = (
    FORGET_DATETIME + "import anyio\n\nasync def main() -> None:\n    pass\n\nanyio.run(main)\n"
) + REPORT

ASYNC_ROBOT = FORGET_DATETIME + (
    "import anyio\n"
    "from j5aio.kit import KitRobot\n\n"
    "async def main() -> None:\n"
    "    async with KitRobot() as robot:\n"
    "        await robot.motor_boards[0].motors[0].set_power(0.5)\n"
    "        print('BOARDS', len(robot.motor_boards), len(robot.cameras), flush=True)\n\n"
    "anyio.run(main)\n" + REPORT
)

#: Modules a robot on the default simulated kit has no use for, each with why.
NOT_NEEDED = {
    "usb": "pyusb: the simulated power and servo boards are not on a USB bus",
    "tomllib": "no kit file is given",
    "json": "no calibration file or other JSON is read",
    "j5aio.simulator.kit_file": "no kit file is given",
    "j5aio.view": "no live view is asked for",
    "j5aio.backends.console": "no board is on the console",
    "j5aio.vision.render": "the camera draws nothing until it is looked through",
    "j5aio.vision.locate": "nothing asks where the robot is",
    "j5aio.vision.geometry": "nothing is measured in the arena",
    "concurrent.futures.thread": "the camera's worker thread waits for a first look",
    "j5aio.vision.worker": "the camera's worker is made at its first look",
    "j5aio.simulator.sr_motor_fw4": "the default kit has no firmware-4 motor board",
    "j5aio.simulator.sr_ruggeduino_fw1": "the default kit has no Ruggeduino",
    "j5aio.backends.hardware.sr.v4.ruggeduino": "the default kit has no Ruggeduino",
    "j5aio.simulator._sim_sr_ruggeduino_fw1": "the default kit has no Ruggeduino",
    "j5aio.boards.sr.v4.motor_board_fw4": "the default kit has no firmware-4 motor board",
    "j5aio.boards.sr.v4.power_board_fw4": "the default kit has no firmware-4 power board",
    "j5aio.boards.sr.v4.arduino": "the default kit has no SR Arduino",
    "j5aio.boards.sb.arduino_2024": "the default kit has no sb2024 Arduino",
    "j5aio.boards.sb.servo_board": "the default kit has no SourceBots servo board",
    "j5aio.boards.sr.v4.servo_board_fw4": "the default kit has no firmware-4 servo board",
    "j5aio.boards.sr.kch": "the default kit has no KCH",
    "j5aio.simulator._camera_model": "the camera's model is read at its first look",
    "j5aio.vision.calibration": "the camera's calibration is read at its first look",
    "j5aio.service": "nothing configures the robot service: its client is not imported",
    "numbers": "the numbers given are ints and floats, which need no number ABCs",
    "j5aio.lifetime": "the safety net's former home: j5aio's own code uses j5aio.safety",
    "j5aio.components.string_command": "the default kit has no Ruggeduino to send commands",
    "j5aio.boards.arduino.all_digital": "the default kit has no all-digital Arduino",
}

#: Modules a robot on the default simulated kit has no use for until it does something
#: (the program starts and ends at once), each with why.
NOT_NEEDED_TO_START = {
    **NOT_NEEDED,
    "j5aio.simulator.arena": "the world is made when the robot first moves or looks",
    "j5aio.simulator.camera": "the camera draws nothing until it is looked through",
    "j5aio.vision.arena_map": "nothing asks where the robot is",
    "j5aio.vision": "nothing is looked at (the camera's worker waits for a first look)",
    "j5aio.competition.metadata": "there is no metadata to read, so the robot develops",
    "j5aio.competition.timer": "no match is started",
    "j5aio.competition.start": "nothing waits for the start",
    "j5aio.simulator._kit_config": "the kit is a named one, not one made from counts",
    "j5aio.components._first": "nothing waits for the start button",
    "j5aio.backends.press_watch": "nothing waits for the start button (the power board's watch)",
    "j5aio._timedelta": "no duration is given or read (a piezo's, an ultrasound echo's)",
    "_datetime": "no duration is given or read (timedelta's C module)",
    "j5aio.components._notes": "no note is named (the piezo's Note enum is made on first use)",
}

STARTED_ROBOT = FORGET_DATETIME + (
    "import anyio\n"
    "from j5aio.kit import KitRobot\n\n"
    "async def main() -> None:\n"
    "    async with KitRobot() as robot:\n"
    "        print('BOARDS', len(robot.motor_boards), len(robot.cameras), flush=True)\n\n"
    "anyio.run(main)\n" + REPORT
)


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def _modules_of(program: str, kit: str | None = None) -> tuple[set[str], str]:
    """The modules loaded at the end of ``program``, run on the simulated kit ``kit``."""
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in {"J5AIO_VIEW", "J5AIO_KIT", "J5AIO_KIT_FILE", "J5AIO_ENV"}
    }
    for key in ("J5AIO_METADATA", "SBOT_METADATA_PATH", "J5AIO_MQTT_URL", "SBOT_MQTT_URL"):
        env.pop(key, None)
    env.update(
        J5AIO_ENV="sim",
        **({"J5AIO_KIT": kit} if kit else {}),
        J5AIO_MEDIA_ROOTS=str(ROOT / "no-media-here"),
        J5AIO_LOCK_PORT=str(_free_port()),
        PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
    )
    done = subprocess.run(
        [sys.executable, "-c", program],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    line = next(line for line in done.stdout.splitlines() if line.startswith("MODULES "))
    return set(json.loads(line.removeprefix("MODULES "))), done.stdout


def _loaded(modules: set[str], name: str) -> bool:
    return any(module == name or module.startswith(f"{name}.") for module in modules)


def _those_loaded(table: dict[str, str], modules: set[str]) -> dict[str, str]:
    """The entries of ``table`` (module: why) whose module, or a submodule, was loaded."""
    return {name: why for name, why in table.items() if _loaded(modules, name)}


@pytest.fixture(scope="module")
def bare_modules() -> set[str]:
    return _modules_of(BARE)[0]


def test_a_robot_on_the_simulated_kit_imports_only_what_it_uses(bare_modules: set[str]) -> None:
    modules, output = _modules_of(ASYNC_ROBOT)
    assert "BOARDS 2 1" in output  # the default kit's motor boards and its camera
    assert _those_loaded(NOT_NEEDED, modules - bare_modules) == {}


def test_a_robot_that_only_starts_loads_no_arena_nor_match(bare_modules: set[str]) -> None:
    modules, output = _modules_of(STARTED_ROBOT)
    assert "BOARDS 2 1" in output
    assert _those_loaded(NOT_NEEDED_TO_START, modules - bare_modules) == {}


def test_the_bare_program_is_a_fair_baseline(bare_modules: set[str]) -> None:
    # (the comparison above would pass vacuously if the baseline had loaded j5aio)
    assert not _loaded(bare_modules, "j5aio")
    assert _loaded(bare_modules, "anyio")


#: The simulators of the boards of the kits before 2023, with their boards.
FIRMWARE_3_SIMULATORS = {
    "j5aio.simulator.sr_power_fw3": "a firmware-3 power board",
    "j5aio.simulator.sr_motor_fw3": "a firmware-3 motor board",
    "j5aio.simulator.sr_servo_fw2": "a firmware-2 servo board",
    "j5aio.simulator.sb_arduino_2019": "a SourceBots Arduino of 2019",
}

#: For each named kit, backends (which a robot asks for all the same) and simulators of
#: boards it does not have, with the board they are of.
OTHER_KITS_BACKENDS = {
    "sr2019": {"j5aio.backends.hardware.sb": "a SourceBots Arduino"},
    "sb2019": {"j5aio.backends.hardware.sr.v4.ruggeduino": "a Ruggeduino"},
    "sr2023": {
        "j5aio.backends.hardware.sb": "a SourceBots Arduino",
        "j5aio.backends.hardware.sr.v4.ruggeduino": "a Ruggeduino",
        "j5aio.backends.hardware.sr.v4.power_board": "a firmware-3 power board",
        "j5aio.backends.hardware.sr.v4.motor_board": "a firmware-3 motor board",
        **FIRMWARE_3_SIMULATORS,
    },
    "sb2024": {
        "j5aio.backends.hardware.sr.v4.arduino": "an SR Arduino",
        "j5aio.backends.hardware.sr.v4.ruggeduino": "a Ruggeduino",
        "j5aio.backends.hardware.sb.arduino": "a SourceBots Arduino of 2019",
        **FIRMWARE_3_SIMULATORS,
    },
}


@pytest.mark.parametrize("kit", sorted(OTHER_KITS_BACKENDS))
def test_a_named_kit_imports_the_backends_and_simulators_of_its_own_boards_only(kit: str) -> None:
    modules, output = _modules_of(STARTED_ROBOT, kit)
    assert "BOARDS 1 1" in output
    assert _those_loaded(OTHER_KITS_BACKENDS[kit], modules) == {}


#: Modules a start leaves to the code that uses them (imported inside it), each with what
#: loads it.
LEFT_TO_THEIR_USERS = {
    "j5aio.lifetime": "code written against the safety net's former home",
    "j5aio.components.string_command": "a Ruggeduino",
    "j5aio.boards.arduino.all_digital": "an SR Arduino or a SourceBots Arduino of 2024",
    "j5aio.components._first": "waiting for the start button",
    "j5aio._timedelta": "a piezo's note, or an ultrasound sensor's echo",
    "_datetime": "a piezo's note, or an ultrasound sensor's echo (timedelta's C module)",
    "j5aio.components._notes": "a program naming a note (Note.A6)",
}

SYNC_ROBOT = FORGET_DATETIME + (
    "from j5aio.sync import KitRobot\n\n"
    "robot = KitRobot()\n"
    "print('BOARDS', len(robot.motor_boards), len(robot.cameras), flush=True)\n" + REPORT
)


def test_a_sync_robot_loads_what_is_left_to_its_users_no_sooner(bare_modules: set[str]) -> None:
    modules, output = _modules_of(SYNC_ROBOT)
    assert "BOARDS 2 1" in output
    assert _those_loaded(LEFT_TO_THEIR_USERS, modules - bare_modules) == {}


USING_THEM = FORGET_DATETIME + (
    "import anyio, sys\n"
    "from j5aio.kit import KitRobot\n\n"
    "async def main() -> None:\n"
    "    async with KitRobot() as robot:\n"
    "        arduinos = [type(board).__name__ for board in robot.arduinos]\n"
    "        ruggeduinos = [type(board.command).__name__ for board in robot.ruggeduinos]\n"
    "        print('USED', arduinos, ruggeduinos, flush=True)\n\n"
    "anyio.run(main)\n" + REPORT
)


@pytest.mark.parametrize(
    ("kit", "used", "expected"),
    [
        ("sr2019", "j5aio.components.string_command", "[] ['StringCommandComponent']"),
        (
            "sr2023",
            "j5aio.boards.arduino.all_digital",
            "['SRArduinoBoard'] ['StringCommandComponent']",
        ),
        ("sb2024", "j5aio.boards.arduino.all_digital", "['SBArduino2024Board'] []"),
    ],
)
def test_what_is_left_to_its_users_is_loaded_when_a_kit_uses_it(
    kit: str, used: str, expected: str
) -> None:
    modules, output = _modules_of(USING_THEM, kit)
    assert f"USED {expected}" in output
    assert used in modules


BUZZING = FORGET_DATETIME + (
    "import anyio, sys\n"
    "from j5aio.kit import KitRobot\n\n"
    "async def main() -> None:\n"
    "    async with KitRobot() as robot:\n"
    "        before = '_datetime' in sys.modules\n"
    "        await robot.power_board.piezo.buzz(0.25, 1760)\n"
    "        from datetime import timedelta\n"
    "        from j5aio.components.piezo import Duration, PiezoInterface\n"
    "        step = robot.power_board.piezo._backend.DURATION_STEP\n"
    "        one_ms = step == PiezoInterface.DURATION_STEP == timedelta(milliseconds=1)\n"
    "        print('BUZZED', before, one_ms, Duration == int | float | timedelta, flush=True)\n\n"
    "anyio.run(main)\n" + REPORT
)


def test_a_note_brings_timedelta_when_it_is_played() -> None:
    modules, output = _modules_of(BUZZING)
    assert "BUZZED False True True" in output  # (not loaded until the note)
    assert {"j5aio._timedelta", "_datetime"} <= modules
