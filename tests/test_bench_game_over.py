"""A bounded run of bench/bench_game_over.py: programs that try to survive game over fail.

Each kind of program (a loop swallowing BaseException, the sync facade sleeping in a
tight loop, a blocking call in an async task, a tight synchronous loop, a program asking
for its boards again, C code holding the GIL, a huge switch interval, a disarmed match
timer, a forked child) is run once with ``j5aio run`` in a short COMP match, under the
match supervisor; its motors must end braked after the match's end (by the simulators'
own record, or by the supervisor ending the process the simulated kit lives in), the
process group must be gone, and ``j5aio run`` must end with status 0 and a Game over line.
The 50 ms and 1 s goals are measured by the bench itself; here the bounds are for
liveness.
"""

from __future__ import annotations

import sys
from types import ModuleType

import pytest

from tests.module_from_file import ROOT, load_module


def load_bench() -> ModuleType:
    return load_module("bench_game_over", ROOT / "bench" / "bench_game_over.py", register=True)


@pytest.mark.skipif(sys.platform == "win32", reason="the match supervisor needs POSIX")
@pytest.mark.parametrize(
    "kind",
    ["swallow", "sync", "blocking", "spin", "sr2023", "reopen", "gil", "switch", "disarm", "fork"],
)
def test_a_program_that_tries_to_survive_game_over_is_stopped(kind: str) -> None:
    bench = load_bench()
    trial = bench.run_trial(kind)
    assert trial.drove, trial  # a motor was driving when the match ended
    assert trial.braked_after is not None, trial
    assert trial.braked_after < 0.5, trial  # liveness; the bench measures the 50 ms goal
    assert trial.returncode == 0, trial
    assert "Game over" in trial.stderr, trial
    assert "Traceback" not in trial.stderr, trial
    assert trial.group_gone_after is not None and trial.group_gone_after < 10, trial
    assert not trial.forked_alive, trial


def test_report_and_braked_after(capsys: pytest.CaptureFixture[str]) -> None:
    bench = load_bench()
    history = [(1.0, "A", ["FORWARD", "BRAKE"]), (2.0, "A", ["BRAKE", "BRAKE"])]
    assert bench.braked_after(history, 1.5) == pytest.approx(0.5)
    assert bench.braked_after([], 1.0) is None
    assert bench.braked_after([(1.0, "A", ["FORWARD", "BRAKE"])], 0.0) is None
    bench.report([
        bench.Trial("spin", 0.01, True, 0, "Game over", group_gone_after=0.3),
        bench.Trial("spin", None, True, 1, "Traceback\nboom", group_gone_after=1.5,
                    forked_alive=True),
    ])
    out = capsys.readouterr().out
    assert "within 50 ms" in out and "still driving" in out
    assert "1 trial(s) with the process group alive after 1000 ms" in out
    assert "a forked child outlived the match" in out
    assert "1 trial(s) without a Game over line" in out
    assert "a failed trial's last line: boom" in out
