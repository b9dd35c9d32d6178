"""A short run of bench/bench_remote_start.py: its broker half runs and prints its figures."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.service.broker import MOSQUITTO

ROOT = Path(__file__).resolve().parents[1]


def test_the_bench_measures_starts_over_the_broker_and_a_restart() -> None:
    pytest.importorskip("aiomqtt")
    if MOSQUITTO is None:
        pytest.skip("mosquitto is not installed (Debian: apt-get install mosquitto)")
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    result = subprocess.run(
        [sys.executable, str(ROOT / "bench" / "bench_remote_start.py"), "2",
         "--broker-rounds", "3", "--restarts", "1"],
        capture_output=True, text=True, timeout=170, cwd=ROOT,
        env={**os.environ, "PYTHONPATH": path}, check=False,
    )
    assert result.returncode == 0, result.stderr
    for words in ("astoria start_button", "sbot start_button", "publish_frame's cost",
                  "client connected again", "remote start works"):
        assert words in result.stdout, result.stdout
