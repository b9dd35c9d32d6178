"""The match supervisor: game over from outside the program's interpreter."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from j5aio.__main__ import main
from j5aio.competition import supervisor
from j5aio.competition.supervisor import SUPERVISOR_FD_VARIABLE, supervise

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="process groups are POSIX's")

ROOT = Path(__file__).resolve().parents[2]

#: The start of a supervised child: it reports a match ending ``END`` seconds from now.
CHILD = """
import os, sys, time
sys.path.insert(0, {root!r})
from j5aio.competition import supervisor
supervisor.report_start(time.monotonic() + {end})
"""


@pytest.fixture(autouse=True)
def _unadopted(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.setattr(supervisor, "_adopted", False)
    monkeypatch.setattr(supervisor, "_pipe", None)
    monkeypatch.delenv(SUPERVISOR_FD_VARIABLE, raising=False)
    yield


def child(end: float, body: str) -> list[str]:
    return [sys.executable, "-c", CHILD.format(root=str(ROOT), end=end) + body]


def gone(pid: int) -> bool:
    """Whether process ``pid`` has ended (a zombie no one reaps counts as ended)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return True
    return state in ("Z", "X")


def test_a_program_holding_the_gil_is_ended_and_its_boards_made_safe() -> None:
    safe_for: list[str | None] = []
    prepared: list[str | None] = []
    said: list[str] = []
    started = time.monotonic()
    status = supervise(
        child(0.2, "while True:\n    sum(range(4 * 10**8))\n"),
        environment="hardware",
        make_safe=safe_for.append,
        prepare=prepared.append,
        say=said.append,
    )
    assert status == 0
    assert prepared == ["hardware"] and safe_for == ["hardware"]
    assert len(said) == 1 and said[0].startswith("Game over: the program did not stop")
    assert time.monotonic() - started < 30  # ended, not waited out


def test_a_program_that_reports_safe_keeps_its_own_game_over_and_its_fork_is_ended(
    tmp_path: Path,
) -> None:
    pid_file = tmp_path / "fork"
    body = f"""
pid = os.fork()
if pid == 0:
    while True:
        time.sleep(1)
open({str(pid_file)!r}, "w").write(str(pid))
supervisor.report_safe()  # as its own game over does
time.sleep(0.3)
os._exit(0)
"""
    safe_for: list[str | None] = []
    status = supervise(child(0.2, body), make_safe=safe_for.append, say=lambda line: None)
    assert status == 0 and safe_for == []  # the program made its boards safe itself
    forked = int(pid_file.read_text())
    deadline = time.monotonic() + 10
    while not gone(forked) and time.monotonic() < deadline:
        time.sleep(0.01)
    assert gone(forked)


def test_a_failure_to_prepare_is_told_and_the_program_still_watched() -> None:
    said: list[str] = []

    def broken(environment: str | None) -> None:
        raise ImportError("no hardware backends")

    command = [sys.executable, "-c", "raise SystemExit(4)"]
    assert supervise(command, prepare=broken, say=said.append) == 4
    assert said == ["j5aio: could not prepare to make the boards safe: "
                    "ImportError('no hardware backends')"]


def test_preparing_loads_the_hardware_backends_only_for_the_hardware(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    loaded: list[str] = []

    class Hardware:
        @property
        def backends(self) -> list[str]:
            loaded.append("backends")
            return []

    monkeypatch.setattr("j5aio.environments.hardware_environment", Hardware)
    supervisor.prepare_boards_safe("sim")
    assert loaded == []
    supervisor.prepare_boards_safe("hardware")
    assert loaded == ["backends"]


def test_a_program_ending_before_the_match_keeps_its_status() -> None:
    assert supervise([sys.executable, "-c", "raise SystemExit(3)"]) == 3
    body = "import signal\nos.kill(os.getpid(), signal.SIGKILL)\n"
    assert supervise(child(60, body)) == 128 + signal.SIGKILL


def test_ctrl_c_and_sigterm_reach_the_program(tmp_path: Path) -> None:
    ready = tmp_path / "ready"
    body = f"""
import signal
signal.signal(signal.SIGTERM, lambda s, f: os._exit(5))
open({str(ready)!r}, "w").close()
while True:
    time.sleep(0.01)
"""

    before = signal.getsignal(signal.SIGTERM)

    def terminate() -> None:
        deadline = time.monotonic() + 30
        # The program is ready, and the supervisor passes the signal on (not this test's
        # own handler, which would end the test run).
        while time.monotonic() < deadline and (
            not ready.exists() or signal.getsignal(signal.SIGTERM) is before
        ):
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGTERM)

    threading.Thread(target=terminate, daemon=True).start()
    assert supervise(child(60, body)) == 5
    assert signal.getsignal(signal.SIGTERM) is before  # given back


def test_the_program_side_reports_over_the_pipe_and_hides_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    read_end, write_end = os.pipe()
    try:
        monkeypatch.setenv(SUPERVISOR_FD_VARIABLE, str(write_end))
        assert supervisor.is_supervised()
        assert SUPERVISOR_FD_VARIABLE not in os.environ  # not passed on to its programs
        supervisor.report_start(12.5)
        supervisor.report_safe()
        supervisor.report_log(Path("/tmp/run.log"))
        assert os.read(read_end, 100) == b"start 12.5\nsafe\nlog /tmp/run.log\n"
    finally:
        os.close(read_end)
        os.close(write_end)
    supervisor.report_safe()  # the supervisor gone: nothing raised


def test_unsupervised_reports_go_nowhere(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(SUPERVISOR_FD_VARIABLE, "not a number")
    assert not supervisor.is_supervised()
    supervisor.report_start(1.0)


def test_the_watch_reads_lines_in_pieces() -> None:
    watch = supervisor._Watch()
    watch.feed(b"start 1")
    assert watch.ends_at is None
    watch.feed(b"2.5\nsta")
    assert watch.ends_at == 12.5 and not watch.safe
    watch.feed(b"rt soon\nnoise\nsafe\nlog /tmp/run 1.log\n")
    assert watch.ends_at == 12.5 and watch.safe and watch.log == "/tmp/run 1.log"


def test_a_run_log_that_cannot_be_written_is_reported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor._append_to_log(None, "Game over")  # no log kept: nothing to do
    supervisor._append_to_log(str(tmp_path / "absent" / "run.log"), "Game over")
    assert "could not add to the run log" in capsys.readouterr().err


def test_only_the_hardware_has_boards_to_stop_after_the_program(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    runs: list[str] = []

    async def fake() -> None:
        runs.append("hardware")

    monkeypatch.setattr(supervisor, "_make_hardware_safe", fake)
    supervisor.make_boards_safe("sim")
    supervisor.make_boards_safe("console")
    assert runs == []
    supervisor.make_boards_safe(None)
    supervisor.make_boards_safe("hardware")
    assert runs == ["hardware", "hardware"]


def test_the_hardware_pass_finds_every_kind_then_makes_all_safe(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    done: list[str] = []

    class Hardware:
        supported_boards = ("MotorBoard", "BrokenBoard", "PowerBoard")

        async def get_board_group(self, kind: str) -> None:
            if kind == "BrokenBoard":
                raise OSError("the port vanished")
            done.append(f"found {kind}")

    async def make_all_safe() -> None:
        done.append("made safe")

    monkeypatch.setattr("j5aio.environments.hardware_environment", Hardware)
    monkeypatch.setattr("j5aio.safety.make_all_safe_uncancellably", make_all_safe)
    supervisor.make_boards_safe("hardware")
    assert done == ["found MotorBoard", "found PowerBoard", "made safe"]


def test_run_supervises_a_timed_match_from_outside(tmp_path: Path) -> None:
    program = tmp_path / "robot.py"
    program.write_text(
        "import anyio\n"
        "from j5aio.kit import KitRobot\n"
        "async def main():\n"
        "    async with KitRobot() as robot:\n"
        "        await robot.wait_start()\n"
        "        await robot.motor_boards[0].motors[0].set_power(0.5)\n"
        "        while True:\n"
        "            sum(range(4 * 10**8))\n"
        "anyio.run(main)\n"
    )
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    env["J5AIO_START_FILE"] = str(tmp_path / "start")
    env["J5AIO_MEDIA_ROOTS"] = str(tmp_path / "media")
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", "--log-dir", str(tmp_path / "logs"),
         "--mode", "comp", "--duration", "0.5", "--start-after", "0.1", str(program)],
        capture_output=True, text=True, env=env, timeout=60, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "Game over: the program did not stop its boards in time" in result.stderr
    (log,) = (tmp_path / "logs").glob("run-*.log")
    assert "[supervisor] Game over: the program did not stop" in log.read_text()


def test_run_supervises_only_timed_matches(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[list[str]] = []

    def fake_supervise(command: list[str], **kwargs: object) -> int:
        calls.append(list(command))
        return 7

    monkeypatch.setattr("j5aio.competition.supervisor.supervise", fake_supervise)
    monkeypatch.setenv("J5AIO_MEDIA_ROOTS", str(tmp_path / "media"))
    monkeypatch.delenv("J5AIO_METADATA", raising=False)
    program = tmp_path / "robot.py"
    program.write_text("")
    args = ["run", "--sim", "--no-log", "--mode", "comp", "--duration", "5", str(program)]
    assert main(args) == 7
    assert calls == [[sys.executable, "-m", "j5aio", *args]]
    assert main(["run", "--sim", "--no-log", "--mode", "dev", str(program)]) == 0
    assert len(calls) == 1
    monkeypatch.setenv("J5AIO_NO_SUPERVISOR", "1")  # a harness that looks into the kit
    assert main(args) == 0
    assert len(calls) == 1
