"""examples/vision_look_around.py runs on the simulated kit and on the console."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "vision_look_around.py"


def run(stdin: str, env: str) -> subprocess.CompletedProcess[str]:
    import os

    return subprocess.run(
        [sys.executable, str(EXAMPLE)],
        input=stdin,
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "J5AIO_ENV": env},
        check=False,
    )


def test_the_example_finds_a_wall_marker_in_the_simulated_arena() -> None:
    result = run("", "sim")
    assert result.returncode == 0, result.stderr
    found = re.search(r"Marker (\d+) is (\d+\.\d+) m straight ahead\.", result.stdout)
    assert found is not None, result.stdout
    assert 0 <= int(found.group(1)) < 28
    assert 0.2 < float(found.group(2)) < 8.2


def test_the_example_asks_on_the_console() -> None:
    result = run("5 2000 1\n", "console")
    assert result.returncode == 0, result.stderr
    assert "Markers seen (id distance_mm bearing_deg, ...)" in result.stdout
    assert "Marker 5 is 2.00 m straight ahead." in result.stdout
