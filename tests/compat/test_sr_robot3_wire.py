"""The same sr-robot3 program sends the same commands whether sr-robot3 or j5aio runs it.

Once sr-robot3 itself (from PyPI) runs ``programs/sr3_wire.py`` against j5aio's simulated
sr2023 boards served on pseudo-terminals; once ``python -m j5aio run --api sr-robot3
--sim --kit sr2023`` runs it. Each board records the bytes it receives; after the
program's first reading of each board (its marker) the commands must be the same, in the
same order, but for the differences listed in :func:`normalised` (each a deliberate
choice of j5aio's, named there).
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections.abc import Callable
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import pytest

from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.serve import PtyServer, serve_on_pty

from .compat_support import PROGRAMS, run_program

if sys.platform == "win32":  # pragma: no cover
    pytest.skip("sr-robot3's boards are served on pseudo-terminals (POSIX only)",
                allow_module_level=True)

SIMULATORS = {
    "sr-power-fw4": "SIMPB0", "sr-motor-fw4": "SIMMB0", "sr-servo-fw4": "SIMSB0",
    "sr-arduino-fw2": "SIMSRA0",
}
BOARD_TYPES = {
    "sr-power-fw4": "PBv4B", "sr-motor-fw4": "MCv4B", "sr-servo-fw4": "SBv4B",
    "sr-arduino-fw2": "Arduino",
}
#: The first reading of each board in the program: what comes before it is discovery.
MARKERS = {
    "sr-power-fw4": "BATT:V?", "sr-motor-fw4": "MOT:0:I?", "sr-servo-fw4": "SERVO:V?",
    "sr-arduino-fw2": "at",
}
ARDUINO_SETUP = """
arduino = kit.simulators("sr-arduino-fw2")[0]
arduino.set_input_level(3, True)
arduino.set_analogue(14, volts=1.25)
arduino.set_ultrasound_distance(4, 5, 0.75)
"""


class ServedKit:
    """The simulated boards, each served on a pseudo-terminal of its own."""

    def __init__(self, boards: dict[str, str]) -> None:
        self.simulators: dict[str, Any] = {
            name: SERIAL_SIMULATORS[name](serial) for name, serial in boards.items()
        }
        self._servers: dict[str, PtyServer] = {
            name: serve_on_pty(simulator, time_scale=0)
            for name, simulator in self.simulators.items()
        }

    def path(self, name: str) -> str:
        """The pseudo-terminal of board ``name``."""
        return self._servers[name].path

    def close(self) -> None:
        for server in self._servers.values():
            server.close()


def commands(board: str, received: str) -> list[str]:
    """Split what a board received into commands: lines, or the Arduino's letters."""
    if board != "sr-arduino-fw2":
        return [line for line in received.split("\n") if line.strip("\x00")]
    found, rest = [], received
    while rest:
        size = 1 if rest[0] == "v" else 3 if rest[0] == "u" else 2
        found.append(rest[:size])
        rest = rest[size:]
    return found


def after_marker(board: str, found: list[str]) -> list[str]:
    return found[found.index(MARKERS[board]):]


def normalised(board: str, found: list[str]) -> list[str]:
    """j5aio's commands with its deliberate differences from sr-robot3 put back.

    - At the end j5aio makes every board safe in its own way (power board ``*RESET``;
      motors braked; servos switched off one by one) where sr-robot3 resets each board:
      what follows the program's last command is compared apart.
    - An Arduino pin made an output first has its level set (``l``/``h``), so that it
      never glitches; sr-robot3 makes it an output at whatever level the latch held.
    """
    if board == "sr-arduino-fw2":
        kept: list[str] = []
        for command in found:
            if command[0] == "o" and kept and kept[-1] in (f"l{command[1]}", f"h{command[1]}"):
                kept.pop()
            kept.append(command)
        return kept
    return found


def strip_end(board: str, found: list[str], peer: bool) -> list[str]:
    """The commands before the end-of-program clean-up."""
    if peer or board == "sr-power-fw4":
        end = ["*RESET"] if board != "sr-arduino-fw2" else []
    elif board == "sr-motor-fw4":
        end = ["MOT:0:SET:0", "MOT:1:SET:0"]  # both motors braked
    elif board == "sr-servo-fw4":
        end = [f"SERVO:{servo}:DISABLE" for servo in range(12)]  # every servo off
    else:
        end = []
    assert found[len(found) - len(end):] == end, (board, found[-15:])
    return found[:len(found) - len(end)]


def recording(log: list[bytes], receive: Callable[[bytes], bytes]) -> Callable[[bytes], bytes]:
    """``receive``, keeping a copy of every byte received in ``log``."""
    def record(data: bytes) -> bytes:
        log.append(bytes(data))
        return receive(data)

    return record


@pytest.fixture
def peer_python() -> str:
    if find_spec("sr") is not None and find_spec("sr.robot3") is not None:
        return sys.executable
    python = os.environ.get("J5AIO_SR_ROBOT3_PYTHON", "")
    if not python:
        pytest.skip(
            "sr-robot3 is not installed: run `tox -e compat-sr-robot3` (it installs "
            "sr-robot3 2026.0.3), or name a Python that has it in J5AIO_SR_ROBOT3_PYTHON"
        )
    return python


def run_sr_robot3(python: str, tmp_path: Path) -> tuple[dict[str, list[str]], str]:
    kit = ServedKit(dict(SIMULATORS))
    try:
        received: dict[str, list[bytes]] = {name: [] for name in SIMULATORS}
        for name, simulator in kit.simulators.items():
            simulator.receive = recording(received[name], simulator.receive)
        arduino = kit.simulators["sr-arduino-fw2"]
        arduino.set_input_level(3, True)
        arduino.set_analogue(14, volts=1.25)
        arduino.set_ultrasound_distance(4, 5, 0.75)
        ports = {BOARD_TYPES[name]: [kit.path(name)] for name in SIMULATORS}
        program = (PROGRAMS / "sr3_wire.py").read_text()
        output = run_sr_robot3_program(python, program, {"WIRE_BOARDS": json.dumps(ports)})
    finally:
        kit.close()
    return {
        name: commands(name, b"".join(chunks).decode("latin-1"))
        for name, chunks in received.items()
    }, output


#: Run before the program: sr-robot3 takes its robot lock on TCP port 10653, which a robot
#: program running beside the tests may hold; it is given a free port instead.
OWN_LOCK_PORT = """
import functools, os, socket
import sr.robot3.robot, sr.robot3.utils
with socket.socket() as probe:
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
sr.robot3.robot.obtain_lock = functools.partial(sr.robot3.utils.obtain_lock, port)
"""


def run_sr_robot3_program(python: str, program: str, env: dict[str, str]) -> str:
    """Run ``program`` with sr-robot3 in ``python``; return what it printed."""
    environment = {
        name: value for name, value in os.environ.items()
        if not name.startswith(("J5AIO", "SBOT_", "WEBOTS_")) and name != "PYTHONPATH"
    }
    result = subprocess.run(
        [python, "-c", OWN_LOCK_PORT + program], capture_output=True, text=True, timeout=120,
        env={**environment, **env}, check=False,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    return result.stdout


def printed(output: str) -> list[str]:
    """The program's own lines of output."""
    program_line = re.compile(r"(marks|motors|servos|h1|pins|distance) ")
    return [line for line in output.splitlines() if program_line.match(line)]


def test_sr_robot3_and_j5aio_send_the_same_commands(peer_python: str, tmp_path: Path) -> None:
    theirs, their_output = run_sr_robot3(peer_python, tmp_path)
    run = run_program("sr3_wire.py", tmp_path, setup=ARDUINO_SETUP)
    assert run.returncode == 0, run.stderr[-3000:]
    for board in SIMULATORS:
        mine_all = commands(board, run.received(board))
        mine = strip_end(board, normalised(board, after_marker(board, mine_all)), peer=False)
        peer = strip_end(board, after_marker(board, theirs[board]), peer=True)
        assert mine == peer, board
    # The start: every output but the brain's switched on, in the same order.
    power_on = [f"OUT:{n}:SET:1" for n in (0, 1, 2, 3, 5, 6)]
    for found in (theirs["sr-power-fw4"], commands("sr-power-fw4", run.received("sr-power-fw4"))):
        start = found.index("OUT:0:SET:1")
        assert found[start:start + 6] == power_on
    # And the program read the same values through both.
    assert printed(their_output) == printed(run.stdout)
    assert len(printed(run.stdout)) == 6
