"""Tests of how a robot starts: on entry, in the background in a match, from the service."""

from __future__ import annotations

import functools
import json
import logging
import sys
import threading
import types
from collections.abc import AsyncIterator
from pathlib import Path

import anyio
import pytest

from j5aio import lifetime
from j5aio import robot as robot_module
from j5aio.boards.board import Board
from j5aio.competition import service_state
from j5aio.competition import timer as timer_module
from j5aio.competition.clock import TIME_SCALE_VARIABLE
from j5aio.competition.metadata import (
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
    MetadataError,
    Mode,
    parse_astoria_metadata,
)
from j5aio.competition.start import START_FILE_VARIABLE, clear_trigger, trigger_start
from j5aio.competition.timer import MatchTimer
from j5aio.errors import CommunicationError
from j5aio.robot import BaseRobot
from j5aio.simulator import kit as kit_module


@pytest.fixture(autouse=True)
async def _fresh(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> AsyncIterator[None]:
    saved = kit_module._current
    monkeypatch.setenv(START_FILE_VARIABLE, str(tmp_path / "start"))
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "media"))
    for name in (METADATA_VARIABLE, SBOT_METADATA_VARIABLE, TIME_SCALE_VARIABLE):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(timer_module, "_hooks", [])
    # No robot service in these tests unless one says so: a module that is not there.
    monkeypatch.setitem(sys.modules, "j5aio.service", None)
    for board in lifetime.open_boards():
        lifetime.untrack(board)
    clear_trigger()
    service_state.clear()
    yield
    clear_trigger()
    service_state.clear()
    for board in list(Board.BOARDS):
        await board.close()
    kit_module._current = saved


@pytest.fixture
def game_over(monkeypatch: pytest.MonkeyPatch) -> threading.Event:
    """Set at game over, instead of the process ending."""
    ended = threading.Event()
    monkeypatch.setattr(
        robot_module,
        "MatchTimer",
        functools.partial(MatchTimer, end_process=lambda code: ended.set(), grace=0),
    )
    return ended


def comp_file(folder: Path, **fields: object) -> Path:
    data: dict[str, object] = {"zone": 2, "is_competition": True}
    data.update(fields)
    path = folder / "metadata.json"
    path.write_text(json.dumps(data))
    return path


def live(**fields: object) -> None:
    service_state.set_metadata(parse_astoria_metadata(fields, "astmetad message"))


async def test_a_match_program_that_never_waits_still_gets_the_timer(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, game_over: threading.Event
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    monkeypatch.setattr("j5aio.competition.metadata.SBOT_MATCH_DURATION", 0.2)
    reached_the_end = False
    async with BaseRobot() as robot:
        assert not robot.started and robot.match_timer is None
        trigger_start("remote start")  # the program never calls wait_start()
        await robot.sleep(30)  # cancelled at game over
        reached_the_end = True
    assert not reached_the_end
    await anyio.to_thread.run_sync(game_over.wait, 10)
    assert game_over.is_set()
    assert robot.started and robot.match_timer is not None


async def test_wait_start_after_the_watcher_saw_the_start_returns_at_once(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, game_over: threading.Event
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    async with BaseRobot() as robot:
        trigger_start()
        assert robot._watcher is not None
        await robot._watcher  # the watcher took the start
        assert robot.started
        await robot.wait_start(timeout=0)  # started already: no wait at all
        assert robot.match_timer is not None
        robot.match_timer._disarm()
        with pytest.raises(RuntimeError, match="wait_start runs once"):
            await robot.wait_start()


async def test_wait_start_waits_for_the_watcher_and_a_timeout_leaves_it_watching(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, game_over: threading.Event
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    async with BaseRobot() as robot:
        with pytest.raises(TimeoutError):
            await robot.wait_start(timeout=0.1)
        assert robot._watcher is not None and not robot._watcher.done()
        with pytest.raises(ValueError, match="timeout"):
            await robot.wait_start(timeout=-1)

        async def later() -> None:
            await anyio.sleep(0.05)
            trigger_start()

        async with anyio.create_task_group() as tasks:
            tasks.start_soon(later)
            await robot.wait_start(timeout=30)
        assert robot.started and robot.zone == 2
        assert robot.match_timer is not None
        robot.match_timer._disarm()


async def test_in_dev_mode_nothing_is_watched() -> None:
    async with BaseRobot() as robot:
        assert robot.mode is Mode.DEV and robot._watcher is None
        trigger_start()
        await anyio.sleep(0.05)
        assert not robot.started  # only the program's own wait takes the start
        await robot.wait_start(timeout=5)
        assert robot.started and robot.match_timer is None


async def test_the_service_can_make_it_a_match_before_the_start(
    game_over: threading.Event,
) -> None:
    async with BaseRobot() as robot:
        assert robot._watcher is None
        await anyio.to_thread.run_sync(
            functools.partial(live, zone=1, mode="DEV")
        )  # from the service's thread
        await anyio.sleep(0.05)
        assert robot.zone == 1 and robot._watcher is None
        await anyio.to_thread.run_sync(
            functools.partial(live, zone=3, mode="COMP", game_timeout=150)
        )
        for _ in range(100):
            if robot._watcher is not None:
                break
            await anyio.sleep(0.01)
        assert robot._watcher is not None and robot.zone == 3
        trigger_start("remote start")
        await robot.wait_start(timeout=30)
        assert robot.match_timer is not None
        robot.match_timer._disarm()
        live(zone=0, mode="DEV")  # after the start: the robot's metadata is fixed
        assert (robot.zone, robot.mode) == (3, Mode.COMP)


async def test_a_bad_file_in_a_match_fails_on_entry(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path, zone="2")))
    with pytest.raises(MetadataError, match=r"metadata.json: field 'zone'"):
        async with BaseRobot():
            pass  # pragma: no cover - not reached
    robot = BaseRobot()
    try:
        with pytest.raises(MetadataError):
            await robot.watch_for_start()
        assert robot._watch_loop is None  # nothing half started: no listener left
        assert robot._on_service_change not in service_state._listeners
    finally:
        robot.release_lock()


async def test_a_failed_watch_is_raised_by_wait_start_then_waited_again(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    from j5aio.competition.start import wait_for_start as real

    calls: list[object] = []

    async def failing_once(boards: object, timeout: float | None = None) -> str:
        calls.append(timeout)
        if len(calls) == 1:
            raise CommunicationError("Power Board X: no answer")
        return await real([], timeout)

    monkeypatch.setattr(robot_module, "wait_for_start", failing_once)
    async with BaseRobot() as robot:
        for _ in range(100):
            if robot._watcher is None:
                break
            await anyio.sleep(0.01)
        assert "Watching for the start failed: Power Board X: no answer" in caplog.text
        with pytest.raises(CommunicationError, match="no answer"):
            await robot.wait_start(timeout=5)
        trigger_start()
        await robot.wait_start(timeout=5)  # waits by itself this time
        assert robot.started and calls == [None, 5]
        assert robot.match_timer is not None
        robot.match_timer._disarm()


async def test_a_bad_service_update_is_logged(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(tmp_path / "m.json"))
    (tmp_path / "m.json").write_text('{"zone": 1}')
    async with BaseRobot() as robot:
        (tmp_path / "m.json").write_text('{"zone": "one"}')
        robot._metadata = None  # as if never read: the file is read again
        robot._look_again()
        assert "The match's metadata is unusable" in caplog.text


async def test_wait_for_start_on_entry(game_over: threading.Event) -> None:
    trigger_start()
    async with BaseRobot(wait_for_start=True) as robot:
        assert robot.started
        with pytest.raises(RuntimeError, match="runs once"):
            await robot.wait_start()
    with pytest.raises(TypeError, match="wait_for_start must be True or False"):
        BaseRobot(wait_for_start=1)  # type: ignore[arg-type]
    BaseRobot().release_lock()  # the refused one gave the lock back


async def test_the_service_is_started_and_stopped_with_the_robot(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    events: list[str] = []

    class FakeService:
        async def stop(self) -> None:
            events.append("stop")

    async def start_service() -> FakeService:
        events.append("start")
        return FakeService()

    fake = types.ModuleType("j5aio.service")
    fake.start_service = start_service  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "j5aio.service", fake)
    monkeypatch.setenv("J5AIO_MQTT_URL", "mqtt://robot.invalid")  # (so the service may be)
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    async with BaseRobot() as robot:
        assert events == ["start"]
        await robot.after_setup()  # started once only
        assert events == ["start"]
    assert events == ["start", "stop"]


async def test_no_service_configured_is_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    async def start_service() -> None:
        return None

    fake = types.ModuleType("j5aio.service")
    fake.start_service = start_service  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "j5aio.service", fake)
    monkeypatch.setenv("J5AIO_MQTT_URL", "mqtt://robot.invalid")
    async with BaseRobot() as robot:
        assert robot._service is None


async def test_a_configured_service_without_its_client_in_this_build_is_nothing(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv("J5AIO_MQTT_URL", "mqtt://robot.invalid")
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    # (the fixture leaves j5aio.service out, as a build without the client would)
    with caplog.at_level(logging.DEBUG, logger="j5aio.robot"):
        async with BaseRobot() as robot:
            assert robot._service is None
    assert "No robot service client in this j5aio" in caplog.text


async def test_where_nothing_configures_the_service_its_client_is_not_imported(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    for name in [name for name in sys.modules if name.startswith("j5aio.service")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setenv("J5AIO_SERVICE", "off")
    async with BaseRobot() as robot:
        assert robot._service is None
    assert not [name for name in sys.modules if name.startswith("j5aio.service")]


async def test_the_services_usercode_stick_is_the_robots(tmp_path: Path) -> None:
    robot = BaseRobot()
    try:
        assert robot.usb_stick is None
        service_state.set_usercode_path(tmp_path / "usercode")
        assert robot.usb_stick == tmp_path / "usercode"
    finally:
        robot.release_lock()


@pytest.mark.parametrize("let_it_run", [False, True])
async def test_leaving_stops_the_watcher(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, let_it_run: bool
) -> None:
    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    async with BaseRobot() as robot:
        watcher = robot._watcher
        if let_it_run:
            await anyio.sleep(0.05)
            assert robot._watch_scope is not None
    assert watcher is not None and watcher.done() and not robot.started
    live(zone=1, mode="COMP", game_timeout=150)  # no longer listened to
    await anyio.sleep(0.05)
    assert robot._watcher is watcher


def test_a_sync_robot_in_a_match_is_watched_too(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, game_over: threading.Event
) -> None:
    import time

    from j5aio.environments import ENVIRONMENT_VARIABLE
    from j5aio.simulator.kit import KitConfig, use_kit
    from j5aio.sync import KitRobot as SyncKitRobot

    monkeypatch.setenv(METADATA_VARIABLE, str(comp_file(tmp_path)))
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "sim")
    use_kit(KitConfig(1, 0, 0, 0, 0))
    robot = SyncKitRobot()  # never calls wait_start
    try:
        assert robot.is_competition and not robot.started
        trigger_start("remote start")
        deadline = time.monotonic() + 10
        while not robot.started and time.monotonic() < deadline:
            time.sleep(0.01)
        assert robot.started
        assert robot.match_timer is not None
        robot.match_timer._disarm()
        robot.wait_start(timeout=0)  # started already: returns at once
    finally:
        robot.release_lock()
