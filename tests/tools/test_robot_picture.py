"""The "Running on the robot" picture is committed, well formed and up to date."""

from __future__ import annotations

import os
import subprocess
import sys
import xml.dom.minidom
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "draw_robot.py"


def run(*args: str) -> subprocess.CompletedProcess[str]:
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, str(TOOL), *args], capture_output=True, text=True, timeout=120,
        cwd=ROOT, env={**os.environ, "PYTHONPATH": path}, check=False,
    )


def test_the_committed_picture_is_up_to_date_and_shown() -> None:
    result = run("--check")
    assert result.returncode == 0, result.stderr
    picture = ROOT / "docs" / "_static" / "on-the-robot.svg"
    document = xml.dom.minidom.parse(str(picture))
    words = " ".join(
        child.data
        for node in document.getElementsByTagName("text")
        for child in node.childNodes
        if isinstance(child, xml.dom.minidom.Text)
    )
    for name in ("astmetad", "astprocd", "Mosquitto", "j5aio", "boards", "stick"):
        assert name in words, name
    assert "_static/on-the-robot.svg" in (ROOT / "docs" / "on-the-robot.rst").read_text()


def test_a_stale_picture_is_reported(tmp_path: Path) -> None:
    assert run("--output", str(tmp_path)).returncode == 0
    (tmp_path / "on-the-robot.svg").write_text("<svg/>", encoding="utf-8")
    result = run("--check", "--output", str(tmp_path))
    assert result.returncode == 1 and "is stale" in result.stderr
