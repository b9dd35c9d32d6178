"""A robot with the real robot service: astoria's messages on a real broker drive the match."""

from __future__ import annotations

import functools
import threading
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
    Mode,
)
from j5aio.competition.start import START_FILE_VARIABLE, clear_trigger
from j5aio.competition.timer import MatchTimer
from j5aio.robot import BaseRobot
from tests.service.broker import Broker
from tests.service.conftest import Peer, broker, peer  # noqa: F401 - fixtures used here
from tests.service.helpers import astmetad_message, astprocd_message, eventually, start_event

pytest.importorskip("aiomqtt", reason="the robot service needs the 'robot' extra (aiomqtt)")


@pytest.fixture(autouse=True)
async def _fresh(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, broker: Broker  # noqa: F811
) -> AsyncIterator[None]:
    monkeypatch.setenv(START_FILE_VARIABLE, str(tmp_path / "start"))
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "media"))
    for name in (METADATA_VARIABLE, SBOT_METADATA_VARIABLE, TIME_SCALE_VARIABLE):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    monkeypatch.setenv("J5AIO_MQTT_URL", f"mqtt://127.0.0.1:{broker.port}/astoria")
    monkeypatch.setattr(timer_module, "_hooks", [])
    for board in lifetime.open_boards():
        lifetime.untrack(board)
    service_state.clear()
    clear_trigger()
    yield
    service_state.clear()
    clear_trigger()
    for board in list(Board.BOARDS):
        await board.close()


async def test_astorias_match_and_remote_start_time_a_program_that_never_waits(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, peer: Peer  # noqa: F811
) -> None:
    ended = threading.Event()
    monkeypatch.setattr(
        robot_module,
        "MatchTimer",
        functools.partial(MatchTimer, end_process=lambda code: ended.set(), grace=0),
    )
    reached_the_end = False
    async with BaseRobot() as robot:
        assert robot.mode is Mode.DEV and robot._service is not None
        await robot._service.wait_connected(timeout=10)
        await peer.publish("astoria/astmetad", astmetad_message(zone=1, mode="DEV"))
        await eventually(lambda: robot.zone == 1)
        await peer.publish("astoria/astprocd", astprocd_message(str(tmp_path / "usercode")))
        await eventually(lambda: robot.usb_stick == tmp_path / "usercode")
        await peer.publish(
            "astoria/astmetad", astmetad_message(zone=2, mode="COMP", game_timeout=1)
        )
        await eventually(lambda: robot._watcher is not None)  # a match now: watched
        await peer.publish("astoria/broadcast/start_button", start_event())
        await eventually(lambda: robot.started)
        await peer.publish("astoria/astmetad", astmetad_message(zone=3, mode="DEV"))
        await eventually(lambda: service_state.metadata() is not None
                         and service_state.metadata().zone == 3)  # type: ignore[union-attr]
        assert (robot.zone, robot.mode) == (2, Mode.COMP)  # fixed at the start
        await robot.sleep(30)  # cancelled at game over
        reached_the_end = True
    assert not reached_the_end
    await anyio.to_thread.run_sync(ended.wait, 10)
    assert ended.is_set()
    assert robot._service is None  # stopped on leaving
