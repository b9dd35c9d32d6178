"""Tests of BaseRobot's match-day API: metadata properties, wait_start, time and sleep."""

from __future__ import annotations

import functools
import json
import threading
from collections.abc import AsyncIterator
from pathlib import Path

import anyio
import pytest

from j5aio import lifetime
from j5aio import robot as robot_module
from j5aio.boards.board import Board
from j5aio.competition import timer as timer_module
from j5aio.competition.clock import TIME_SCALE_VARIABLE
from j5aio.competition.metadata import (
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
    Mode,
)
from j5aio.competition.start import START_FILE_VARIABLE, clear_trigger, trigger_start
from j5aio.competition.timer import MatchTimer
from j5aio.kit import KitRobot
from j5aio.robot import BaseRobot
from j5aio.simulator import kit as kit_module
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode


@pytest.fixture(autouse=True)
async def _fresh(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> AsyncIterator[None]:
    saved = kit_module._current
    monkeypatch.setenv(START_FILE_VARIABLE, str(tmp_path / "start"))
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "media"))
    monkeypatch.delenv(METADATA_VARIABLE, raising=False)
    monkeypatch.delenv(SBOT_METADATA_VARIABLE, raising=False)
    monkeypatch.delenv(TIME_SCALE_VARIABLE, raising=False)
    monkeypatch.setattr(timer_module, "_hooks", [])
    for board in lifetime.open_boards():  # boards other tests left: not this test's kit
        lifetime.untrack(board)
    clear_trigger()
    yield
    clear_trigger()
    for board in list(Board.BOARDS):
        await board.close()
    kit_module._current = saved


def metadata_file(folder: Path, **fields: object) -> Path:
    data = {"arena": "B", "zone": 3, "mode": "COMP", "duration": 0.3, "marker_offset": 0}
    data.update(fields)
    path = folder / "metadata.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data))
    return path


async def test_dev_defaults_before_and_after_the_start() -> None:
    robot = BaseRobot()
    try:
        assert (robot.arena, robot.zone, robot.mode, robot.is_competition) == (
            "A", 0, Mode.DEV, False,
        )
        assert robot.usb_stick is None
        trigger_start()
        await robot.wait_start(timeout=5)
        assert robot.match_timer is None  # DEV: no match timer
        with pytest.raises(RuntimeError, match="started already"):
            await robot.wait_start()
    finally:
        robot.release_lock()


async def test_metadata_from_a_stick(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    stick = tmp_path / "media" / "ROBOT"
    metadata_file(stick, mode="DEV", zone=1)
    monkeypatch.setattr(
        "j5aio.competition.metadata.os.path.ismount", lambda path: Path(path) == stick
    )
    robot = BaseRobot()
    try:
        assert robot.zone == 1 and robot.arena == "B"
        assert robot.usb_stick == stick
    finally:
        robot.release_lock()


async def test_a_comp_match_ends_with_the_boards_safe(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(metadata_file(tmp_path)))
    monkeypatch.setenv(TIME_SCALE_VARIABLE, "0.5")  # the 0.3 s match lasts 0.15 s
    ended = threading.Event()
    monkeypatch.setattr(
        robot_module,
        "MatchTimer",
        functools.partial(MatchTimer, end_process=lambda code: ended.set(), grace=0),
    )
    kit = use_kit(KitConfig(1, 1, 0, 0, 0))
    reached_the_end = False
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        trigger_start()
        await robot.wait_start(timeout=5)
        assert robot.is_competition and robot.zone == 3 and robot.arena == "B"
        assert robot.time() < 0.1  # the clock restarts at the start
        timer = robot.match_timer
        assert timer is not None and timer.remaining() is not None
        await robot.motor_boards[0].motors[0].set_power(0.5)
        await robot.sleep(10)  # cancelled at game over
        reached_the_end = True
    assert not reached_the_end
    await anyio.to_thread.run_sync(ended.wait, 5)
    assert ended.is_set()
    assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE


async def test_a_bad_metadata_file_fails_the_start(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(metadata_file(tmp_path, zone="two")))
    robot = BaseRobot()
    try:
        trigger_start()
        with pytest.raises(ValueError, match=r"metadata.json: field 'zone'"):
            await robot.wait_start(timeout=5)
    finally:
        robot.release_lock()


def test_the_sync_facade_has_plain_properties(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from j5aio import sync

    monkeypatch.setenv(METADATA_VARIABLE, str(metadata_file(tmp_path, mode="DEV", zone=5)))
    robot = sync.BaseRobot()
    try:
        assert (robot.zone, robot.arena, robot.mode, robot.is_competition) == (5, "B", "DEV", False)
        assert robot.usb_stick is None and robot.metadata.zone == 5
        trigger_start()
        robot.wait_start(timeout=5)
        assert robot.match_timer is None
        robot.sleep(0.01)
        assert robot.time() >= 0.01
    finally:
        robot.release_lock()
