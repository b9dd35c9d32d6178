"""The docs' pictures: the layer diagrams are up to date, and a recorded run is drawn."""

from __future__ import annotations

import os
import subprocess
import sys
import xml.dom.minidom
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TOOLS = ROOT / "tools"
STATIC = ROOT / "docs" / "_static"


def tool(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, *args], capture_output=True, text=True, timeout=120, cwd=cwd,
        env={**os.environ, "PYTHONPATH": path}, check=False,
    )


def test_the_committed_layer_diagrams_are_up_to_date() -> None:
    result = tool(str(TOOLS / "draw_layers.py"), "--check")
    assert result.returncode == 0, result.stderr


def test_a_stale_layer_diagram_is_reported(tmp_path: Path) -> None:
    assert tool(str(TOOLS / "draw_layers.py"), "--output", str(tmp_path)).returncode == 0
    (tmp_path / "layers-team.svg").write_text("<svg/>", encoding="utf-8")
    result = tool(str(TOOLS / "draw_layers.py"), "--check", "--output", str(tmp_path))
    assert result.returncode == 1
    assert "layers-team.svg is stale" in result.stderr


def test_every_picture_the_docs_show_is_committed_and_well_formed() -> None:
    pages = "".join(p.read_text(encoding="utf-8") for p in (ROOT / "docs").glob("*.rst"))
    for name in ("layers-overview", "layers-student", "layers-team", "layers-volunteer",
                 "run-student", "run-team"):
        assert f"_static/{name}.svg" in pages, name
        xml.dom.minidom.parse(str(STATIC / f"{name}.svg"))


def test_a_recorded_run_shows_what_the_simulated_boards_did(tmp_path: Path) -> None:
    picture = tmp_path / "run.svg"
    result = tool(
        str(TOOLS / "plot_kit_run.py"), str(ROOT / "examples" / "sync_blink_and_drive.py"),
        "-o", str(picture), "--title", "a test run",
    )
    assert result.returncode == 0, result.stderr
    assert "Zig-zag done" in result.stdout
    document = xml.dom.minidom.parse(str(picture))
    assert document.getElementsByTagName("title")[0].firstChild.data == "a test run"  # type: ignore[union-attr]
    traces = document.getElementsByTagName("polyline")
    assert len(traces) == 5
    # motor 1 went backwards (below its band's zero line) while turning; pin 13 went high
    heights = [
        [float(point.split(",")[1]) for point in trace.getAttribute("points").split()]
        for trace in traces
    ]
    assert len(set(heights[1])) >= 3  # stopped, forwards, backwards
    assert len(set(heights[4])) == 2  # pin 13: low and high


def test_recording_samples_the_simulators(tmp_path: Path) -> None:
    program = tmp_path / "spin.py"
    program.write_text(
        "import time\n"
        "from j5aio.sync import KitRobot\n"
        "robot = KitRobot()\n"
        "robot.motor_boards[0].motors[0].power = -1\n"
        "time.sleep(0.2)\n",
        encoding="utf-8",
    )
    script = (
        "import sys; sys.path.insert(0, sys.argv[1])\n"
        "import plot_kit_run\n"
        "rec = plot_kit_run.record(__import__('pathlib').Path(sys.argv[2]), pin=13,"
        " interval=0.005, title='t')\n"
        "print(min(v for _, v in rec.traces[0].samples), rec.traces[0].name)\n"
    )
    result = tool("-c", script, str(TOOLS), str(program))
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["-1.0", "motor", "0", "power"]
