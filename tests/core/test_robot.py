from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import anyio
import pytest

from j5aio.boards.board_group import BoardGroup
from j5aio.errors import UnableToObtainLock
from j5aio.robot import BaseRobot

from .conftest import LampBackend, LampBoard


class LampRobot(BaseRobot):
    async def setup(self) -> None:
        self.lamps = await BoardGroup.get_board_group(LampBoard, LampBackend)


async def test_boards_made_safe_on_normal_exit() -> None:
    async with LampRobot() as robot:
        assert robot.lamps[0].lamp_backend.states[0] is True
        assert robot.boards() == set(robot.lamps.boards)
    assert [b.safe_calls for b in robot.lamps] == [1, 1]


async def test_boards_made_safe_when_the_block_raises() -> None:
    with pytest.raises(ZeroDivisionError):
        async with LampRobot() as robot:
            1 / 0  # noqa: B018
    assert all(b.safe_calls == 1 for b in robot.lamps)


async def test_boards_made_safe_when_a_task_group_fails() -> None:
    async def crash() -> None:
        await anyio.sleep(0.01)
        raise RuntimeError("sensor task failed")

    with pytest.raises(ExceptionGroup):
        async with LampRobot() as robot, anyio.create_task_group() as tg:
            tg.start_soon(crash)
            tg.start_soon(anyio.sleep, 10)
    assert all(b.safe_calls == 1 for b in robot.lamps)


async def test_boards_made_safe_when_cancelled() -> None:
    robots: list[LampRobot] = []
    with anyio.move_on_after(0.05):
        async with LampRobot() as robot:
            robots.append(robot)
            await anyio.sleep(10)
    assert all(b.safe_calls == 1 for b in robots[0].lamps)


async def test_only_one_robot_at_a_time() -> None:
    async with LampRobot():
        with pytest.raises(UnableToObtainLock, match="another robot program"):
            LampRobot()
    async with LampRobot():  # the lock was released on exit
        pass


async def test_failed_setup_releases_the_lock_and_makes_safe() -> None:
    class Broken(BaseRobot):
        async def setup(self) -> None:
            raise OSError("no boards")

    with pytest.raises(OSError, match="no boards"):
        async with Broken():
            pass
    robot = BaseRobot()
    robot.release_lock()


def test_the_lock_message_names_the_port_and_the_variable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("J5AIO_LOCK_PORT", "0")
    first = BaseRobot()
    assert first._lock is not None
    port = first._lock.getsockname()[1]
    monkeypatch.setenv("J5AIO_LOCK_PORT", str(port))
    try:
        with pytest.raises(UnableToObtainLock, match=f"TCP port {port} .*J5AIO_LOCK_PORT"):
            BaseRobot()
    finally:
        first.release_lock()


def test_lock_held_by_another_process() -> None:
    code = "import time, j5aio; r = j5aio.BaseRobot(); print('ready', flush=True); time.sleep(30)"
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        assert proc.stdout.readline().strip() == "ready"
        with pytest.raises(UnableToObtainLock):
            BaseRobot()
    finally:
        proc.kill()
        proc.wait()


SIGTERM_PROGRAM = textwrap.dedent(
    """
    import asyncio, sys
    sys.path.insert(0, {tests!r})
    from core.conftest import LampBackend, LampBoard
    from j5aio import BaseRobot, BoardGroup

    class R(BaseRobot):
        async def setup(self):
            self.lamps = await BoardGroup.get_board_group(LampBoard, LampBackend)

    async def main():
        robot = R()
        try:
            async with robot:
                print("running", flush=True)
                await asyncio.sleep(30)
        finally:
            print("safe", [b.safe_calls for b in robot.lamps], flush=True)

    asyncio.run(main())
    """,
)


def start_running_robot(*, measured: bool = True) -> subprocess.Popen[str]:
    """Start SIGTERM_PROGRAM in a child Python and wait until its robot runs.

    :param measured: let coverage measure the child, if the suite runs under coverage.
        Without it the child's output is j5aio's alone: coverage's own exit hook, torn by
        a second Ctrl-C, prints a traceback of its own.
    """
    tests = os.path.dirname(os.path.dirname(__file__))
    environment = None
    if not measured:
        environment = {k: v for k, v in os.environ.items() if not k.startswith("COVERAGE_")}
    proc = subprocess.Popen(
        [sys.executable, "-c", SIGTERM_PROGRAM.format(tests=tests)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=environment,
    )
    assert proc.stdout is not None
    assert proc.stdout.readline().strip() == "running"
    return proc


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_signal_makes_boards_safe_and_stops(signum: int) -> None:
    proc = start_running_robot()
    started = time.monotonic()
    try:
        proc.send_signal(signum)
        out, err = proc.communicate(timeout=10)
    finally:
        proc.kill()  # a robot program left running would keep the robot lock
        proc.wait()
    assert time.monotonic() - started < 5
    assert "safe [1, 1]" in out
    if signum == signal.SIGINT:
        assert proc.returncode in (-signal.SIGINT, 128 + signal.SIGINT)
        assert err == "Stopped (Ctrl-C); every board was made safe.\n"
    else:
        # One clear line and the conventional status; no CancelledError traceback.
        assert proc.returncode == 128 + signum
        assert err == f"Terminated by {signal.Signals(signum).name}: making every board safe.\n"


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_twice_prints_one_line() -> None:
    # The second Ctrl-C comes while the program is ending: after the robot made its boards
    # safe, in asyncio's teardown, the exit hooks or the safety net. (One that comes before
    # the robot's own stop may cut it short; the safety net then finishes the job, which
    # tests/test_lifetime.py checks on simulated boards.)
    proc = start_running_robot(measured=False)
    assert proc.stdout is not None
    try:
        proc.send_signal(signal.SIGINT)
        assert proc.stdout.readline() == "safe [1, 1]\n"
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=10)
    finally:
        proc.kill()  # a robot program left running would keep the robot lock
        proc.wait()
    assert "Traceback" not in err
    assert "Exception ignored" not in err
