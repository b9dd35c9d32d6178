"""The same sbot program sends the same commands to each board, under sbot and under j5aio.

``programs/sbot_wire.py`` runs twice: once with sbot itself (from PyPI), talking over
pseudo-terminals to j5aio's simulators of the sb2024 kit's boards (as tests/peers does),
and once with ``j5aio.compat.sbot`` on the simulated sb2024 kit. Each board's received
lines are compared from the program's first command to that board, so that finding the
boards (which the two do differently) is left aside, and sbot's reset of the boards when
it exits (j5aio makes them safe instead) is too.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.serve import PtyServer, serve_on_pty

from .test_sbot_api_surface import PEER_VERSION, _peer_python
from .test_sbot_programs import PROGRAMS, run_sbot_program

if sys.platform == "win32":  # pragma: no cover
    pytest.skip("the boards are served on pseudo-terminals (POSIX only)", allow_module_level=True)

#: Per board (sbot's kit simulator, j5aio's serial number): the program's first command.
BOARDS = {
    "sr-power-fw4": ("SIMPB0", "OUT:0:GET?"),
    "sb-motor-fw4": ("SIMMB0", "MOT:0:GET?"),
    "sb-servo-fw4": ("SIMSB0", "SERVO:0:GET?"),
    "sb-arduino-2024": ("SIMSBA0", "PIN:2:DIGITAL:GET?"),
}

#: Where j5aio sends a command sbot does not, on purpose: before a pin becomes an output
#: j5aio sets the level it will drive (the last one written, low at first), so that the
#: pin does not briefly drive what its pull-up left in the latch.
J5AIO_EXTRA = {"sb-arduino-2024": ["PIN:13:DIGITAL:SET:0"]}


def _from(lines: list[str], first: str) -> list[str]:
    assert first in lines, (first, lines)
    return lines[lines.index(first):]


def _run_sbot(python: str) -> dict[str, list[str]]:
    """Run the program with sbot, its boards served on ptys; return each board's lines."""
    received: dict[str, list[str]] = {}
    servers: dict[str, PtyServer] = {}
    try:
        for name, (serial, _) in BOARDS.items():
            simulator = SERIAL_SIMULATORS[name](serial)
            received[name] = _record(simulator)
            servers[name] = serve_on_pty(simulator, time_scale=0)
        environment = {
            key: value for key, value in os.environ.items()
            if not key.startswith(("SBOT_", "J5AIO"))
        }
        environment.update({
            "SBOT_SKIP_WAIT_START": "1",
            "SBOT_MANUAL_POWER_PORTS": servers["sr-power-fw4"].path,
            "SBOT_MANUAL_MOTOR_PORTS": servers["sb-motor-fw4"].path,
            "SBOT_MANUAL_SERVO_PORTS": servers["sb-servo-fw4"].path,
            "SBOT_MANUAL_ARDUINO_PORTS": servers["sb-arduino-2024"].path,
        })
        result = subprocess.run(
            [python, str(PROGRAMS / "sbot_wire.py")],
            capture_output=True, text=True, timeout=120, env=environment,
            cwd=Path(PROGRAMS), check=False,
        )
        assert result.returncode == 0, result.stderr[-3000:]
    finally:
        for server in servers.values():
            server.close()
    return received


def _record(simulator: object) -> list[str]:
    """Make ``simulator`` keep each line it receives; return the list they go into."""
    lines: list[str] = []
    partial = [b""]
    receive = simulator.receive  # type: ignore[attr-defined]

    def recording(data: bytes) -> bytes:
        *complete, partial[0] = (partial[0] + bytes(data)).split(b"\n")
        lines.extend(line.decode("utf-8", "replace") for line in complete)
        return receive(data)  # type: ignore[no-any-return]

    simulator.receive = recording  # type: ignore[attr-defined]
    return lines


def test_sbot_and_the_compat_package_send_the_same_commands() -> None:
    python = _peer_python()
    if python is None:
        pytest.skip(
            f"sbot is not installed: run `tox -e compat-sbot` (it installs sbot=={PEER_VERSION} "
            "from PyPI), or set SBOT_PEER_PYTHON to a Python that has it",
        )
    by_sbot = _run_sbot(python)
    process, _, kit = run_sbot_program("sbot_wire.py", env={"SBOT_SKIP_WAIT_START": "1"})
    assert process.returncode == 0, process.stderr[-3000:]
    for name, (serial, first) in BOARDS.items():
        theirs = _from(by_sbot[name], first)
        while theirs and theirs[-1] == "*RESET":  # sbot's clean-up at exit
            theirs.pop()
        ours = _from(kit["received"][serial], first)
        extra = list(J5AIO_EXTRA.get(name, []))
        ours = [line for line in ours if not (extra and line == extra[0] and extra.pop(0))]
        assert extra == [], (name, extra)
        assert ours == theirs, name
        assert len(theirs) > 3, (name, theirs)
