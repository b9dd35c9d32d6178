"""A bounded run of bench/bench_signals.py: busy programs stopped by a signal brake."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def load_bench() -> ModuleType:
    path = Path(__file__).resolve().parents[1] / "bench" / "bench_signals.py"
    spec = importlib.util.spec_from_file_location("bench_signals", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


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
