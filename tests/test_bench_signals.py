"""A bounded run of bench/bench_signals.py: busy programs stopped by a signal brake."""

from __future__ import annotations

import sys
from types import ModuleType

import pytest

from tests.module_from_file import ROOT, load_module

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def load_bench() -> ModuleType:
    return load_module("bench_signals", ROOT / "bench" / "bench_signals.py", register=True)


def test_busy_programs_are_braked_soon_after_a_signal(capsys: pytest.CaptureFixture[str]) -> None:
    bench = load_bench()
    results = bench.run_trials(2, seed=7)
    assert len(results) == 4  # sync and async, SIGINT and SIGTERM
    for trial in results:
        assert trial.braked_after is not None, trial
        assert trial.braked_after < 2.0, trial  # liveness only: the bench measures the goal
        assert "Traceback" not in trial.stderr, trial
        assert "Exception ignored" not in trial.stderr, trial
        if trial.signal_name == "SIGTERM":
            assert trial.returncode == 143, trial
    bench.report(results)
    assert "within 50 ms" in capsys.readouterr().out


def test_braked_after_needs_every_board_safe_for_good() -> None:
    bench = load_bench()
    history = [
        (1.0, "A", ["FORWARD", "BRAKE"]),
        (2.0, "B", ["BRAKE", "BRAKE"]),
        (3.0, "A", ["BRAKE", "BRAKE"]),
    ]
    assert bench.braked_after(history, 2.5) == pytest.approx(0.5)
    assert bench.braked_after([*history, (4.0, "B", ["REVERSE", "BRAKE"])], 2.5) is None
    assert bench.braked_after([], 1.0) is None
