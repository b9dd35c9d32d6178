"""The safety net: programs that never close their boards leave them safe, however they end.

Each program runs in a child Python on the simulated kit (or attaches to a simulator
served on a pseudo-terminal by this process), drives a motor and switches an output on,
then ends in one of the ways the net must catch. What the simulators do at the very end
of the child is checked: for the in-process kit, an ``atexit`` hook registered before
anything else (so it runs after every other exit hook) prints the simulators' state; for
the pty simulator, this process reads it once the child has gone.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from j5aio.simulator import MotorMode, SRMotorBoardFw3Simulator
from j5aio.simulator.serve import serve_on_pty

ROOT = Path(__file__).resolve().parents[1]


def child_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    return env

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and ptys")

SAFE_MODES = {MotorMode.BRAKE.name, MotorMode.COAST.name}

DUMP_AT_THE_VERY_END = """
import atexit, json

def _dump():
    from j5aio.simulator.kit import current_kit
    kit = current_kit()
    state = {
        "motors": [m.mode.name for b in kit.motor_boards for m in b.motors],
        "outputs": [o for b in kit.power_boards for o in b.outputs],
    }
    print("STATE " + json.dumps(state), flush=True)

atexit.register(_dump)  # first registered, so it runs last
"""

DRIVE = """
import anyio
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.environments import get_default_environment
from j5aio.simulator.kit import current_kit


async def drive():
    environment = get_default_environment()
    power = await environment.get_board_group(PowerBoard)
    await power[0].outputs[1].set_is_enabled(True)  # the motor boards' 12 V (H0, H1)
    await power[0].outputs[0].set_is_enabled(True)
    motors = await environment.get_board_group(MotorBoard)
    await motors[0].motors[0].set_power(0.5)
    await motors[1].motors[1].set_power(-1)
    kit = current_kit()
    assert kit.motor_boards[0].motors[0].mode.name == "FORWARD"
    assert kit.power_boards[0].outputs[0]
    print("driving", flush=True)
"""

ENDINGS: dict[str, str] = {
    # A beginner's script: the loop finishes; the state is looked at right after it too.
    "loop end": """
anyio.run(drive)
kit = current_kit()
print("after the loop", [m.mode.name for b in kit.motor_boards for m in b.motors], flush=True)
""",
    # A loop that is never finished: only the interpreter's exit is left.
    "normal exit": """
import asyncio
loop = asyncio.new_event_loop()
loop.run_until_complete(drive())
""",
    "unhandled exception": """
async def main():
    await drive()
    raise RuntimeError("student bug")

anyio.run(main)
""",
    "unhandled exception, loop never finished": """
import asyncio
loop = asyncio.new_event_loop()
loop.run_until_complete(drive())
raise RuntimeError("student bug")
""",
    "SIGTERM": """
async def main():
    await drive()
    await anyio.sleep(30)

anyio.run(main)
""",
}


def start_child(source: str, *args: str, env: dict[str, str]) -> subprocess.Popen[str]:
    """Start ``source`` in a child Python with pipes for its output."""
    return subprocess.Popen(
        [sys.executable, "-c", source, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=ROOT,
    )


def run_child(
    source: str, *, env: dict[str, str], signum: int | None = None
) -> tuple[int, str, str]:
    process = start_child(source, env=env)
    try:
        assert process.stdout is not None
        before = []
        if signum is not None:
            for line in process.stdout:
                before.append(line)
                if line.startswith("driving"):
                    break
            time.sleep(0.1)
            process.send_signal(signum)
        out, err = process.communicate(timeout=20)
    finally:
        process.kill()
    return process.returncode, "".join(before) + out, err


def final_state(out: str) -> dict[str, Any]:
    lines = [line for line in out.splitlines() if line.startswith("STATE ")]
    assert lines, f"no state dumped: {out!r}"
    assert out.rstrip().splitlines()[-1] == lines[-1], "the state was not the last word"
    state: dict[str, Any] = json.loads(lines[-1].removeprefix("STATE "))
    return state


def sim_env() -> dict[str, str]:
    env = child_env()
    env["J5AIO_ENV"] = "sim"
    env.pop("J5AIO_LOG", None)
    return env


def assert_safe(state: dict[str, Any]) -> None:
    assert state["motors"], state
    assert set(state["motors"]) <= SAFE_MODES, state
    assert state["outputs"], state
    assert not any(state["outputs"]), state


@pytest.mark.parametrize("ending", list(ENDINGS))
def test_boards_of_an_async_program_without_a_robot_end_safe(ending: str) -> None:
    signum = signal.SIGTERM if ending == "SIGTERM" else None
    code, out, err = run_child(
        DUMP_AT_THE_VERY_END + DRIVE + ENDINGS[ending], env=sim_env(), signum=signum
    )
    assert "driving" in out, err
    assert_safe(final_state(out))
    # One line per rescued board: the two motor boards and the power board.
    rescued = [line for line in err.splitlines() if "made safe by j5aio's safety net" in line]
    assert len(rescued) == 3, err
    if ending.startswith("unhandled exception"):
        assert code == 1
        assert "RuntimeError: student bug" in err
    elif ending == "SIGTERM":
        assert code == 128 + signal.SIGTERM
        assert "Terminated by SIGTERM" in err
        assert "Traceback" not in err
    else:
        assert code == 0, err
    if ending == "loop end":
        after = next(line for line in out.splitlines() if line.startswith("after the loop"))
        assert "FORWARD" not in after and "REVERSE" not in after


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_a_signal_to_a_program_whose_loop_is_busy_elsewhere(signum: int) -> None:
    # The loop never runs again after the drive: the signal arrives in plain sync code.
    source = DUMP_AT_THE_VERY_END + DRIVE + """
import asyncio
loop = asyncio.new_event_loop()
loop.run_until_complete(drive())
time.sleep(30)
"""
    code, out, err = run_child("import time\n" + source, env=sim_env(), signum=signum)
    assert code == 128 + signum
    assert_safe(final_state(out))
    assert f"Terminated by {signal.Signals(signum).name}" in err


ATTACH = """
import anyio, sys
from j5aio.backends.hardware.sr.v4 import SRV4MotorBoardHardwareBackend

async def drive():
    board = await SRV4MotorBoardHardwareBackend.attach(sys.argv[1])
    await board.motors[0].set_power(0.75)
    await board.motors[1].set_power(-0.25)
    print("driving", flush=True)
"""

ATTACH_ENDINGS = {
    "loop end": "anyio.run(drive)\nprint('after the loop', flush=True)\n",
    "normal exit": (
        "import asyncio\nasyncio.new_event_loop().run_until_complete(drive())\n"
    ),
    "unhandled exception": (
        "async def main():\n    await drive()\n    raise RuntimeError('student bug')\n"
        "anyio.run(main)\n"
    ),
    "SIGTERM": "async def main():\n    await drive()\n    await anyio.sleep(30)\nanyio.run(main)\n",
    "SIGHUP": "async def main():\n    await drive()\n    await anyio.sleep(30)\nanyio.run(main)\n",
}


class RecordingMotorSimulator(SRMotorBoardFw3Simulator):
    """Remembers every mode its motor 0 took, in order."""

    def __init__(self, serial_number: str) -> None:
        super().__init__(serial_number)
        self.history: list[str] = []

    def receive(self, data: bytes) -> bytes:
        reply = b""
        for byte in data:  # a chunk may hold the drive and the brake commands both
            reply += super().receive(bytes((byte,)))
            self.history.append(self.motors[0].mode.name)
        return reply


def safe(simulator: SRMotorBoardFw3Simulator) -> bool:
    return {motor.mode.name for motor in simulator.motors} <= SAFE_MODES


@pytest.mark.parametrize("ending", list(ATTACH_ENDINGS))
def test_a_board_attached_by_port_ends_safe(ending: str) -> None:
    simulator = RecordingMotorSimulator("PTY")
    with serve_on_pty(simulator, time_scale=0) as server:
        signum = getattr(signal, ending, None)
        env = child_env()
        env.pop("J5AIO_ENV", None)
        process = start_child(ATTACH + ATTACH_ENDINGS[ending], server.path, env=env)
        try:
            assert process.stdout is not None
            first = process.stdout.readline()
            assert first.startswith("driving"), process.stderr.read() if process.stderr else ""
            # The server thread applies what the child wrote; let it catch up.
            deadline = time.monotonic() + 5
            while MotorMode.FORWARD.name not in simulator.history:
                assert time.monotonic() < deadline, simulator.history
                time.sleep(0.01)
            if signum is not None:
                process.send_signal(signum)
            _, err = process.communicate(timeout=20)
        finally:
            process.kill()
        # The child has gone; give the server thread time to apply its last bytes.
        deadline = time.monotonic() + 3
        while not safe(simulator) and time.monotonic() < deadline:
            time.sleep(0.01)
        modes = {motor.mode.name for motor in simulator.motors}
    assert modes <= SAFE_MODES, (modes, err)
    assert "made safe by j5aio's safety net" in err
    if signum is not None:
        assert process.returncode == 128 + signum
    elif ending == "unhandled exception":
        assert process.returncode == 1
    else:
        assert process.returncode == 0, err


def test_the_log_names_each_rescued_board_once() -> None:
    code, _, err = run_child(DUMP_AT_THE_VERY_END + DRIVE + ENDINGS["loop end"], env=sim_env())
    assert code == 0
    rescued = sorted(line for line in err.splitlines() if "safety net" in line)
    assert len(rescued) == len(set(rescued)) == 3
    assert all("when its event loop finished" in line for line in rescued)
    assert os.linesep.join(rescued).count("SIMMB0") == 1


SR2023_DUMP_AT_THE_VERY_END = """
import atexit, json

def _dump():
    from j5aio.simulator.kit import current_kit
    kit = current_kit()
    state = {
        "motors": [m.drive.name for b in kit.simulators("sr-motor-fw4") for m in b.motors],
        "outputs": [o for b in kit.simulators("sr-power-fw4") for o in b.outputs],
    }
    print("STATE " + json.dumps(state), flush=True)

atexit.register(_dump)  # first registered, so it runs last
"""

SR2023_DRIVE = """
import anyio
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, PowerBoardOutput
from j5aio.environments import get_default_environment
from j5aio.simulator.kit import current_kit


async def main():
    environment = get_default_environment()
    power = (await environment.get_board_group(PowerBoardFw4)).singular()
    await power.outputs[PowerBoardOutput.H0].set_is_enabled(True)  # the motor board's 12 V
    await power.outputs[PowerBoardOutput.L3].set_is_enabled(True)
    motor = (await environment.get_board_group(MotorBoardFw4)).singular()
    await motor.motors[0].set_power(0.5)
    await motor.motors[1].set_power(-1)
    kit = current_kit()
    assert kit.simulators("sr-motor-fw4")[0].motors[0].drive.name == "FORWARD"
    assert kit.simulators("sr-power-fw4")[0].outputs[0]
    print("driving", flush=True)
    await anyio.sleep(30)

anyio.run(main)
"""


def test_the_sr2023_kit_ends_braked_and_powered_off_on_sigterm() -> None:
    env = sim_env()
    env["J5AIO_KIT"] = "sr2023"
    code, out, err = run_child(
        SR2023_DUMP_AT_THE_VERY_END + SR2023_DRIVE, env=env, signum=signal.SIGTERM
    )
    assert "driving" in out, err
    assert code == 128 + signal.SIGTERM, err
    state = final_state(out)
    assert state["motors"] == ["BRAKE", "BRAKE"], state
    # The motor board was braked before the power board cut its 12 V: had the power gone
    # first, braking would have failed, and said so.
    assert "Could not make" not in err, err
    # Every output off but L2, the brain's, which the board keeps on.
    assert state["outputs"] == [False, False, False, False, True, False, False], state
    rescued = [line for line in err.splitlines() if "made safe by j5aio's safety net" in line]
    assert len(rescued) == 2, err
