"""sbot-style programs run unchanged on the simulated sb2024 kit (``j5aio.compat.sbot``).

Each program runs in a child ``python -m j5aio run --api sbot --sim --kit sb2024
--start-after 0`` (``--api sbot``: ``import sbot`` gives the compatibility package) under
``programs/sbot_harness.py``, which sets the kit's inputs and prints what the simulated
boards did at the end.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
PROGRAMS = Path(__file__).resolve().parent / "programs"


def _free_port() -> str:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return str(probe.getsockname()[1])


def run_sbot_program(
    name: str,
    *options: str,
    kit: str | None = "sb2024",
    env: dict[str, str] | None = None,
    cwd: Path = ROOT,
) -> tuple[subprocess.CompletedProcess[str], dict[str, Any], dict[str, Any]]:
    """Run ``programs/<name>`` on a simulated kit; return the process, RESULT and KIT."""
    environment = {
        key: value for key, value in os.environ.items()
        if not key.startswith(("SBOT_", "J5AIO_"))
    }
    environment.update({
        "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
        "J5AIO_LOCK_PORT": _free_port(),
        "SBOT_HARNESS_BENCH": "1",
        "SBOT_HARNESS_RECORD": "1",
        **(env or {}),
    })
    process = subprocess.run(
        [
            sys.executable, "-m", "j5aio", "run", "--api", "sbot", "--sim",
            *(["--kit", kit] if kit else []), "--start-after", "0", "--no-log", *options,
            str(PROGRAMS / "sbot_harness.py"), str(PROGRAMS / name),
        ],
        capture_output=True, text=True, timeout=120, env=environment, cwd=cwd, check=False,
    )
    found: dict[str, dict[str, Any]] = {"RESULT": {}, "KIT": {}, "EXIT": {}}
    for line in process.stdout.splitlines():
        tag, _, data = line.partition(" ")
        if tag in found:
            found[tag] = json.loads(data)
    found["KIT"]["exit"] = found["EXIT"]
    return process, found["RESULT"], found["KIT"]


def test_a_team_program_drives_the_kit_as_under_sbot() -> None:
    process, _, kit = run_sbot_program("sbot_drive.py")
    assert process.returncode == 0, process.stderr[-3000:]
    lines = [line for line in process.stdout.splitlines() if " - " not in line]
    assert lines[:5] == [
        "zone 0 competition False",
        "powers 0.5 0.5",
        "turning -0.25",
        # 0.5 between sbot's default limits (350-1980 µs) is 1572 µs, which the board
        # keeps as 1570 (5 µs steps): it reads back as 0.497, as under sbot.
        "servo 1.0 -1.0 0.497",
        # The ADC's 512 of 1023 is 2.502 V; the ultrasound gives whole millimetres.
        "sensors True False 2.502 500",
    ]
    # The battery, in volts and amps (the simulated kit's load makes it sag and draw).
    _, volts, amps = lines[5].split()
    assert 11 < float(volts) <= 12.25 and 0 < float(amps) < 20
    assert lines[6] == "current 0.75"
    # sbot switched on every output; the brain's (L2) was on anyway.
    assert kit["outputs"] == [True] * 7
    assert kit["motors"] == [["BRAKE", 0], ["COAST", 0]]
    assert kit["servos"][:4] == [1980, 350, 1570, None]
    assert kit["pins"]["3"] == ["INPUT_PULLUP", True]
    assert kit["pins"]["13"] == ["OUTPUT", True]
    assert kit["received"]["SIMPB0"][-1] == "NOTE:1760:500"
    # At the end, as sbot's reset of the boards: servos off, outputs off but the brain's;
    # the motors brake (j5aio's safe state; sbot's reset lets them coast).
    end = kit["exit"]
    assert end["servos"] == [None] * 8
    assert end["outputs"] == [False, False, False, False, True, False, False]
    assert end["motors"] == [["BRAKE", 0], ["BRAKE", 0]]
    motor_lines = kit["received"]["SIMMB0"]
    assert motor_lines[-4:] == ["MOT:1:GET?", "MOT:0:I?", "MOT:0:SET:0", "MOT:1:DISABLE"]
    # sbot's log lines, where a volunteer reads them.
    assert "sbot._utils - INFO - Waiting for start button." in process.stdout
    assert "sbot._utils - INFO - Start button pressed." in process.stdout
    assert "Index: 1  =>  serial: SIMMB0, output 1" in process.stdout


def test_every_call_and_every_wrong_call_answers_as_sbot() -> None:
    process, got, kit = run_sbot_program("sbot_probe.py")
    assert process.returncode == 0, process.stderr[-3000:]
    # Errors: sbot's types and messages.
    assert got["too_fast"] == ["ValueError", "Motor power is a float between -1.0 and 1.0"]
    assert got["word_power"][0] == "TypeError"
    assert got["no_motor"] == ["ValueError", "Output 5 does not exist on motor board"]
    assert got["negative_motor"][0] == "AssertionError"
    assert got["brain"] == ["RuntimeError", "Brain output cannot be controlled via this API."]
    assert got["no_output"] == ["ValueError", "Output 9 does not exist on power board"]
    assert got["output_word"][0] == "TypeError"
    assert got["low_limit"][0] == "ValueError" and got["float_limit"][0] == "TypeError"
    assert got["no_servo"] == ["ValueError", "Output 8 does not exist on servo board"]
    assert got["far_servo"] == ["ValueError", "Servo position is a float between -1.0 and 1.0"]
    assert got["serial_pin"] == ["OSError", "This pin cannot be controlled."]
    assert got["no_pin"] == ["IndexError", "Pin 25 is not available on the Arduino."]
    assert got["mode_word"][0] == "OSError"
    assert got["digital_analog"] == ["OSError", "Pin does not support analog read"]
    assert got["pulled_analog"][0] == "OSError" and "INPUT_PULLUP" in got["pulled_analog"][1]
    assert got["output_analog"][0] == "OSError" and "OUTPUT mode" in got["output_analog"][1]
    assert got["bad_pulse_pin"] == ["ValueError", "Invalid pulse pin provided"]
    assert got["bad_echo_pin"] == ["ValueError", "Invalid echo pin provided"]
    assert got["no_led"] == ["ValueError", "Invalid LED ID: 3"]
    assert got["negative_sleep"][0] == "ValueError"
    assert got["low_note"][0] == "ValueError" and got["long_note"][0] == "ValueError"
    assert got["reload"] == ["RuntimeError", "Boards have already been loaded"]
    assert got["restart"] is None  # a second wait for the start, as sbot allows
    # Readings.
    assert got["motor_status"] == [[False, False], 12.0, []]
    assert got["in_fault"] is False
    assert got["after_reset"] == [-1024, -1024]  # reset: both motors coast
    assert got["h1"] is False and got["h0_current"] == 0.0
    assert got["power_status"] == [[False] * 7, 25, False, 5.0]
    assert got["reversed"] == [[2000, 1000], 0.25]
    assert got["equal"] == [1500, 1500]
    assert got["disabled"] is None
    assert got["servo_status"] == [False, True]
    assert got["servo_rail"] == [0.0, 5.5]
    assert got["read_output"] is True
    assert got["a1_digital_then_analog"] == [False, 0.0]
    assert got["no_echo"] == 0
    assert got["led"] == "MAGENTA"  # the kit's HAT (KCH) lights it
    vision = got["vision"]
    assert vision["shape"] == [720, 1280, 3]
    assert vision["files"] == ["raw.jpg", "seen.png"]
    assert vision["ids"] and vision["same"] and vision["distance_is_int"]
    assert vision["sizes"] == [100]  # the arena's markers, 0 to 27, are 100 mm
    assert vision["repr"].startswith(f"<Marker id={vision['ids'][0]} distance=")
    assert got["reprs"] == ["<Motor SIMMB0>", "<Servo SIMSB0>", "<Power SIMPB0>",
                            "<Arduino SIMSBA0>"]
    assert got["after_power_reset"] is False
    # The board state the calls left.
    # sbot's pulses for a reversed servo (0.25 between 2000 and 1000 µs: 1375 µs) and
    # for equal limits reach the board, though j5aio's limits must rise.
    assert "SERVO:3:SET:1375" in kit["received"]["SIMSB0"]
    assert "SERVO:4:SET:1500" in kit["received"]["SIMSB0"]
    assert kit["servos"] == [None] * 8  # the program ends with servos.reset()
    assert kit["pins"]["7"] == ["INPUT_PULLUP", True]  # written high while an input
    assert kit["pins"]["10"] == ["INPUT", False]
    assert kit["outputs"] == [False, False, False, False, True, False, False]


def test_a_program_that_finds_the_boards_itself() -> None:
    process, got, kit = run_sbot_program(
        "sbot_start.py", "--zone", "2", env={"SBOT_SKIP_WAIT_START": "1"},
    )
    assert process.returncode == 0, process.stderr[-3000:]
    assert got["before_load"].startswith("Boards cannot be accessed before they are loaded")
    assert "wait_start" in got["zone_early"]
    assert got["reprs"] == ["<Power no power board>", "<Arduino no arduino connected>"]
    assert got["zone"] == 2 and got["competition"] is False
    assert kit["motors"][1] == ["FORWARD", 250]


def test_a_match_ends_the_program_quietly_as_sbot_does() -> None:
    process, _, _ = run_sbot_program(
        "sbot_match.py", "--mode", "COMP", "--zone", "3", "--duration", "1",
    )
    assert "zone 3 competition True" in process.stdout
    assert "sbot.internal.timeout - INFO - Timeout expired: Game Over!" in process.stdout
    assert process.returncode == 0, process.stderr[-3000:]
    assert "Traceback" not in process.stderr


def test_on_the_simulator_an_sbot_program_gets_sourcebots_kit() -> None:
    process, _, kit = run_sbot_program(
        "sbot_wire.py", kit=None, env={"SBOT_SKIP_WAIT_START": "1", "SBOT_HARNESS_BENCH": "0"},
    )
    assert process.returncode == 0, process.stderr[-3000:]
    assert "Simulated kit: sb2024 (SourceBots' kit)" in process.stdout
    assert "SERVO:0:SET:1572" in kit["received"]["SIMSB0"]  # the 8-servo SourceBots board


def test_the_example_of_sbots_readme_runs_unchanged() -> None:
    process, _, kit = run_sbot_program(
        "sbot_readme.py", "--mode", "COMP", "--duration", "60",
    )
    assert process.returncode == 0, process.stderr[-3000:]
    lines = [line for line in process.stdout.splitlines() if " - " not in line]
    assert lines[0] == "500"  # the bench's obstacle, 0.5 m away, in mm
    assert lines[1].startswith("markers [") and lines[1] != "markers []"
    assert kit["motors"] == [["FORWARD", 300], ["FORWARD", 300]]
    assert kit["servos"][0] == 1570  # 45/90 is 0.5: 1572 µs, kept in 5 µs steps
    assert "NOTE:880:500" in kit["received"]["SIMPB0"]  # (played while it looked)


def test_sbots_override_file_in_the_working_directory_is_read(tmp_path: Path) -> None:
    # The README's override.env (NO_POWERBOARD is not supported: the robot has one).
    (tmp_path / "override.env").write_text(
        "ENABLE_DEBUG_LOGGING=1\nSKIP_WAIT_START=1\nNO_POWERBOARD=1\n", encoding="utf-8",
    )
    process, _, kit = run_sbot_program("sbot_readme_start.py", cwd=tmp_path)
    assert process.returncode == 0, process.stderr[-3000:]
    assert "root - DEBUG - Debug Mode is enabled" in process.stdout
    assert "started" in process.stdout.splitlines()
    assert kit["motors"][0] == ["REVERSE", -500]


def test_sbots_metadata_file_gives_the_zone_and_the_mode(tmp_path: Path) -> None:
    stick = tmp_path / "usb"
    stick.mkdir()
    (stick / "metadata.json").write_text('{"zone": 2, "is_competition": true}')
    process, got, _ = run_sbot_program(
        "sbot_start.py",
        env={"SBOT_SKIP_WAIT_START": "1", "SBOT_METADATA_PATH": str(tmp_path)},
    )
    assert process.returncode == 0, process.stderr[-3000:]
    assert got["zone"] == 2 and got["competition"] is True
    assert "The match has started: it ends in 150 s." in process.stdout  # sbot's length


def test_a_competition_robot_runs_on_the_simulated_arena() -> None:
    process, _, kit = run_sbot_program("sbot_team.py")
    assert process.returncode == 0, process.stderr[-3000:]
    assert "starting in zone 0" in process.stdout
    summary = next(line for line in process.stdout.splitlines() if line.startswith("steps"))
    assert "saw markers True" in summary
    assert kit["motors"] == [["BRAKE", 0], ["BRAKE", 0]]
    assert kit["servos"][0] is None
    assert "SERVO:0:SET:500" in kit["received"]["SIMSB0"]  # open, under its own limits
