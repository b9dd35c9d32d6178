"""sr-robot3 programs, as teams write them, run unchanged on the simulated sr2023 kit.

Each runs under ``python -m j5aio run --api sr-robot3 --sim --kit sr2023`` in a child
process (see :mod:`.compat_support`); the tests look at what it printed and at what each
simulated board received and was left in.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from .compat_support import run_program

ARDUINO_INPUTS = """
arduino = kit.simulators("sr-arduino-fw2")[0]
arduino.set_input_level(3, True)
arduino.set_input_level(4, False)
arduino.set_analogue(14, volts=2.5)
arduino.set_ultrasound_distance(6, 7, 0.5)
"""


def test_a_driving_program_sends_sr_robot3s_commands(tmp_path: Path) -> None:
    run = run_program("sr3_drive.py", tmp_path, "--start-after", "0")
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("powers") == "0.5 -0.25"
    assert run.line("braked") == "0.0"
    assert run.line("coasting") == "True"
    assert run.line("servo") == "0.5"
    assert run.line("reversed") == "0.5 (2000, 1000)"
    assert run.line("off") == "None"
    assert run.line("outputs on") == str([True] * 7)
    l1, h0_current = run.line("L1").split(" H0 current ")
    assert l1 == "False" and float(h0_current) >= 0
    assert run.line("battery") == "True True"
    assert run.line("identity") == "['Student Robotics', 'PBv4B'] ['Student Robotics', 'MCv4B']"
    assert run.line("serials") == "['SIMMB0'] ['SIMSB0']"
    motor = run.received("sr-motor-fw4")
    # thousandths truncated as sr-robot3 does (0.1234 -> 123), BRAKE is 0, COAST disables
    for command in ("MOT:0:SET:500", "MOT:1:SET:-250", "MOT:0:SET:123", "MOT:1:SET:0",
                    "MOT:1:DISABLE"):
        assert f"\n{command}\n" in motor
    servo = run.received("sr-servo-fw4")
    assert "SERVO:2:SET:1750\n" in servo
    assert "SERVO:2:SET:1250\n" in servo  # 0.5 between 2000 and 1000 µs
    power = run.received("sr-power-fw4")
    # Every output but L2 (the brain's) switched on at start, once, in order, before the
    # other boards are looked for, as sr-robot3 does.
    assert power.startswith(
        "*IDN?\n*RESET\nOUT:0:SET:1\nOUT:1:SET:1\nOUT:2:SET:1\nOUT:3:SET:1\nOUT:5:SET:1\n"
        "OUT:6:SET:1\nBTN:START:GET?\n")
    # The start: a beep and the run LED flashing, then lit.
    assert "NOTE:1760:100\nLED:RUN:SET:F\nLED:RUN:SET:1\n" in power
    assert "NOTE:1047:250\nNOTE:440:11\nNOTE:1000:50\n" in power
    assert "OUT:3:SET:0\n" in power
    # At the end: power board reset, servos off (as sr-robot3's resets), motors stopped.
    assert power.endswith("*RESET\n")
    assert run.state("sr-power-fw4")["outputs"] == [False] * 4 + [True] + [False] * 2
    assert run.state("sr-servo-fw4")["pulse_widths"] == [None] * 12
    assert set(run.state("sr-motor-fw4")["motors"]) <= {"MotorDrive.BRAKE", "MotorDrive.COAST"}
    # sr-robot3's log lines, where a volunteer reads them
    for line in ("sr.robot3.robot - INFO - Found PowerBoard, serial: SIMPB0",
                 "sr.robot3.robot - INFO - Found MotorBoard, serial: SIMMB0",
                 "sr.robot3.robot - INFO - Found Arduino, serial: SIMSRA0",
                 "sr.robot3.robot - INFO - Waiting for start button.",
                 "sr.robot3.robot - INFO - Start signal received; continuing."):
        assert line in run.stdout


def test_a_sensing_program_reads_volts_millimetres_and_levels(tmp_path: Path) -> None:
    run = run_program("sr3_sensors.py", tmp_path, setup=ARDUINO_INPUTS)
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("digital") == "True False"
    assert run.line("analogue") == "2.502 0.0"  # ADC 512 / 1023 x 5, as sr-robot3 reads it
    assert run.line("ultrasound") == "500 0"  # mm, and 0 for no echo
    assert run.line("after ultrasound") == "GPIOPinMode.INPUT False"
    assert run.lines("output reads back") == ["True", "False"]
    assert run.line("A0 as digital") == "True"
    assert run.line("A0 again") == "2.502"
    assert run.line("command") == "SRduino:2"
    assert run.line("pin letter") == "t"
    assert run.line("identity") == "['Student Robotics', 'SRduino', 'SIMSRA0', '2']"
    arduino = run.received("sr-arduino-fw2")
    # pull-up on 3, input on 4, both read, A0 and A1 read, ultrasound on 6-7 and 8-9, pin 6
    # read after the firmware left it an output (so put back to input first)
    assert "pdierdreaoapughuijigrg" in arduino
    # pin 13: an output driven high then low (read back with no traffic), A0 pulled up and
    # read, then an input read as volts
    assert arduino.endswith("lnonhnlnporoioaov")  # and the raw command "v"
    # no start was waited for (wait_for_start=False): nothing but the outputs switched on
    assert "BTN:START" not in run.received("sr-power-fw4")


def test_a_programs_mistakes_raise_sr_robot3s_errors(tmp_path: Path) -> None:
    run = run_program("sr3_errors.py", tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    expected = {
        "zone before start": "MetadataNotReadyError Metadata (zone, arena and mode) can only "
        "be used after wait_start has been called",
        "metadata error is a RuntimeError": "True",
        "disconnection is an OSError": "True",
        "power too high": "ValueError Motor power is a float between -1.0 and 1.0",
        "power not a number": "TypeError Motor power is a float between -1.0 and 1.0",
        "servo too far": "ValueError Servo position is a float between -1.0 and 1.0",
        "duty limits": "ValueError Servo pulse limits are ints in µs, in the range 500 to 4000",
        "duty limit types": "TypeError Servo pulse limits are ints in µs, in the range 500 "
        "to 4000",
        "brain output": "RuntimeError Brain output cannot be controlled via this API.",
        "buzz too high": "ValueError Frequency must be between 8 and 10000Hz",
        "buzz negative": "ValueError Duration is a float in seconds between 0 and 2,147,484",
        "write to input": "OSError Digital write is not supported in GPIOPinMode.INPUT",
        "analogue on digital pin": "OSError Pin does not support analog read",
        "analogue on output": "OSError Analog read is not supported in GPIOPinMode.OUTPUT",
        "serial pin read": "OSError This pin cannot be controlled.",
        "serial pin mode": "OSError This pin cannot be controlled.",
        "mode not a mode": "OSError Pin mode only supports being set to a GPIOPinMode",
        "bad pulse pin": "ValueError Invalid pulse pin provided",
        "bad echo pin": "ValueError Invalid echo pin provided",
        "subclass": "TypeError MyRobot cannot be sub-classed.",
    }
    for what, outcome in expected.items():
        assert run.line(what) == outcome, what
    assert run.line("two robots").startswith("UnableToObtainLock ")  # an OSError
    assert run.line("done") == ""
    # Nothing wrong reached a board: only the start-up, pin 15's two modes and H0 on.
    assert run.received("sr-motor-fw4").count("MOT:0:SET") == 1  # the end's stop only
    assert run.received("sr-arduino-fw2").endswith("lpopip")


def test_a_match_program_sees_its_zone_and_ends_at_game_over(tmp_path: Path) -> None:
    run = run_program(
        "sr3_match.py", tmp_path, "--start-after", "0.1", "--zone", "2", "--arena", "B",
        "--mode", "comp", "--duration", "1",
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("start") == "2 B RobotMode.COMP True True"
    assert run.line("usbkey") == "True"
    assert "the match timer did not end the program" not in run.stdout
    assert "sr.robot3.robot - INFO - Timeout set: 1s" in run.stdout
    assert "sr.robot3.timeout - INFO - Timeout expired: Game Over!" in run.stdout
    assert "Traceback" not in run.stderr
    assert run.received("sr-motor-fw4").count("MOT:0:SET:300") >= 2
    assert run.received("sr-motor-fw4").endswith("MOT:0:SET:0\nMOT:1:SET:0\n")


def test_a_program_lights_the_kch_and_sees_markers(tmp_path: Path) -> None:
    run = run_program(
        "sr3_leds_camera.py", tmp_path, "--start-after", "0", arguments=(str(tmp_path),))
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("leds") == "(True, False, True) (True, True, False)"
    assert run.line("channels") == "True False True"
    assert run.line("markers") == "True True"
    assert run.line("fields") == "int int int 4 True True"
    assert run.line("saved") == "True True 3"
    assert run.line("from frame") == "True"
    assert run.line("camera") == "camera True"


#: A competition runner that presses start again and again (by the start file).
KEEP_STARTING = """
import threading, time
from pathlib import Path

import pytest
def keep_starting():
    while True:
        time.sleep(0.2)
        Path({path!r}).touch()
threading.Thread(target=keep_starting, daemon=True).start()
"""


def test_a_program_on_the_2019_kit_and_sr_robot3s_rarer_calls(tmp_path: Path) -> None:
    run = run_program(
        "sr3_old_kit.py", tmp_path, kit="sr2019",
        setup=KEEP_STARTING.format(path=str(tmp_path / "start")),
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("debug") == "True"
    assert "sr.robot3.robot - DEBUG - Firmware Version of SIMRD0: 1" in run.stdout
    assert "manual_boards is not needed on j5aio" in run.stdout
    assert "Raw ports are not available in the simulator." in run.stdout
    assert run.line("arduinos") == "['SIMRD0']"
    assert run.line("raw") == "{}"
    assert run.line("outputs") == "6 False"  # a firmware 3 board: six outputs, no trips
    assert run.line("off") == str([False] * 6)
    assert run.line("motor reads") == "0.25 0.0 False"  # no current sense on firmware 3
    assert run.line("reset") == "True"
    assert run.line("servo reset").endswith("cannot unpower a servo (position None); give a "
                                            "position between -1 and 1")
    assert run.line("servo position") == "-1.0"
    for what in ("power status", "servo status", "servo current"):
        assert run.line(what) == "BoardDisconnectionError"  # firmware 3 / 2 report none
    assert run.line("motor status") == (
        "MotorStatus(output_faults=(False, False), input_voltage=0.0, other=[])")
    assert run.line("kch") == "(False, False, False) False"  # no KCH: the LEDs do nothing
    assert run.line("colour") == "The LED requires 3 values for it's colour"
    assert run.line("key error") == "Key 'zone' not present in metadata"
    assert run.line("command") == "OSError"  # SR's Ruggeduino firmware takes none
    assert run.line("ultrasound") == "OSError"
    assert run.line("reprs") == "True True <Pin index=2 analog=False disabled=False>"
    assert run.line("time") == "True"
    assert run.line("started twice") == "0"
    assert run.stdout.count("Start signal received; continuing.") == 2
    assert "VID:PID - Manufacturer - Product - Serial Number" in run.stdout


def test_a_robot_without_a_power_board(tmp_path: Path) -> None:
    run = run_program(
        "sr3_no_power_board.py", tmp_path, "--start-after", "0",
        setup="from j5aio.board_kinds import KitDefinition\n"
        "from j5aio.simulator.kit import use_kit\n"
        "use_kit(KitDefinition('motors-only', 'a motor board alone', {'sr-motor-fw4': 1}))\n",
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("power board") == "No power board was initialized"
    assert run.line("motor") == "-0.5 RobotMode.DEV"
    assert "MOT:0:SET:-500\n" in run.received("sr-motor-fw4")


def test_a_board_that_goes_away_raises_sr_robot3s_disconnection_error(tmp_path: Path) -> None:
    run = run_program("sr3_unplugged.py", tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("caught") == "True j5aio.errors"  # j5aio's error is the cause
    assert run.line("still running") == "True"
    assert run.received("sr-motor-fw4").endswith("MOT:0:SET:500\n")  # nothing after


def test_with_every_cable_pulled_each_call_raises_the_disconnection_error(
    tmp_path: Path,
) -> None:
    run = run_program("sr3_all_unplugged.py", tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("reprs") == (
        "<Outputs: <Output <Led <BatterySensor: <Piezo: <MotorBoard: <Motor <ServoBoard: "
        "<Servo <Arduino: <Pin <AprilCamera:")
    assert run.line("types") == "MCv4B SBv4B Arduino Camera PBv4B"
    assert run.line("status") == "25 True True False"
    assert run.line("failed") == "28 of 29"
    assert run.line("worked") == "['servo limits']"  # (kept by j5aio: nothing is sent)


def test_the_api_works_with_the_live_view(tmp_path: Path) -> None:
    from j5aio.view import web_stack_installed

    if not web_stack_installed():
        pytest.skip("the live view needs the 'view' extra (aiohttp)")
    run = run_program("sr3_drive.py", tmp_path, "--start-after", "0", "--view")
    assert run.returncode == 0, run.stderr[-3000:]
    assert "http://127.0.0.1:" in run.stderr + run.stdout
    assert run.line("powers") == "0.5 -0.25"


def test_sr_robot3s_documented_uses(tmp_path: Path) -> None:
    run = run_program("sr3_docs_tour.py", tmp_path, "--start-after", "0", "--zone", "3")
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.lines("tour") == [
        "motors 0.5", "battery True", "arduino True True", "vision True",
        "metadata 3 A RobotMode.DEV",
    ]
    power = run.received("sr-power-fw4")
    assert "OUT:0:SET:0\nOUT:6:SET:1\nNOTE:1000:500\nNOTE:2349:250\n" in power
    motor = run.received("sr-motor-fw4")
    assert "MOT:0:SET:1000\nMOT:1:SET:-1000\nMOT:1:SET:500\nMOT:0:DISABLE\n" in motor
    assert "SERVO:0:SET:1250\n" in run.received("sr-servo-fw4")


def test_the_command_line_itself_runs_an_sr_robot3_program(tmp_path: Path) -> None:
    import os
    import subprocess
    import sys

    from .compat_support import PROGRAMS, ROOT

    env = {k: v for k, v in os.environ.items() if not k.startswith(("J5AIO_ENV", "J5AIO_KIT"))}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    env["J5AIO_START_FILE"] = str(tmp_path / "start")
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--api", "sr-robot3", "--sim", "--kit", "sr2023",
         "--start-after", "0", "--log-dir", str(tmp_path / "logs"),
         str(PROGRAMS / "sr3_drive.py")],
        capture_output=True, text=True, timeout=90, env=env, cwd=tmp_path, check=False,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert "powers 0.5 -0.25" in result.stdout
    logs = list((tmp_path / "logs").glob("run-*.log"))
    assert len(logs) == 1 and "Found MotorBoard, serial: SIMMB0" in logs[0].read_text()


def test_the_module_works_imported_by_its_own_name(tmp_path: Path) -> None:
    run = run_program("sr3_direct_import.py", tmp_path, api=None)
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.line("direct") == "0.75 False"
    assert "MOT:1:SET:750\n" in run.received("sr-motor-fw4")


def test_trace_logging_shows_the_wire_traffic(tmp_path: Path) -> None:
    run = run_program("sr3_trace.py", tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    assert "root - TRACE - Trace Mode is enabled" in run.stdout
    assert "- TRACE - -> b'MOT:0:SET:500\\n'" in run.stdout
