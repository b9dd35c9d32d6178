"""Locating on the simulated kit: real pictures, the real detector, async and sync."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import pytest

from tests.module_from_file import load_module

pytest.importorskip("numpy")
pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

from j5aio.kit import KitRobot
from j5aio.simulator.arena import Pose
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import use_kit
from j5aio.vision.locate import locate
from j5aio.vision.track import PositionTracker

pytestmark = pytest.mark.usefixtures("fresh_kit")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def load_example(name: str) -> ModuleType:
    return load_module(name, EXAMPLES / f"{name}.py")


async def test_a_robot_on_the_simulated_kit_locates_itself_from_one_picture() -> None:
    kit = use_kit()
    pose = Pose(1200.0, 3400.0, -0.6)
    kit.world.place_robot(pose)
    arena_map = kit.world.arena.arena_map()
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is not None
        where = locate(await robot.camera.see(), arena_map, kit.world.camera_mount())
        assert where is not None and len(where.used) >= 2
        assert math.hypot(where.x - pose.x, where.y - pose.y) < 30
        assert abs(math.remainder(where.heading - pose.heading, math.tau)) < math.radians(1)
        tracker = PositionTracker(robot.camera, arena_map, kit.world.camera_mount())
        estimate = await tracker.update()
        assert estimate is not None
        assert math.hypot(estimate.x - pose.x, estimate.y - pose.y) < 30


async def test_the_drive_to_a_token_tutorial_reaches_its_token(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("J5AIO_ENV", "sim")
    kit = use_kit()
    example = load_example("drive_to_token")
    target = await example.main()
    faces = [face for token in kit.world.arena.tokens for face in token.markers()]
    face = min(faces, key=lambda f: math.hypot(f.x - target[0], f.y - target[1]))
    # The program knew where the token was, and stopped where it meant to.
    assert math.hypot(face.x - target[0], face.y - target[1]) < 50
    pose = kit.world.pose
    assert math.hypot(face.x - pose.x, face.y - pose.y) == pytest.approx(
        example.STOP_AT, abs=100
    )
    assert "Stopped at" in capsys.readouterr().out


def test_the_sync_form_of_the_tutorial_runs_on_the_simulated_kit() -> None:
    result = subprocess.run(
        [sys.executable, str(EXAMPLES / "sync_drive_to_token.py")],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "J5AIO_ENV": "sim", "PYTHONPATH": str(EXAMPLES.parent)},
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "Token 10" in result.stdout and "Stopped at (" in result.stdout
