"""The service client against a real mosquitto, with the peers' exact payloads."""

from __future__ import annotations

import json
import logging
from collections.abc import AsyncIterator, Callable
from pathlib import Path

import anyio
import pytest

from j5aio.competition import service_state
from j5aio.competition.metadata import Mode
from j5aio.competition.start import wait_for_start
from j5aio.service import RobotService, ServiceConfig, current_service, publish_frame
from j5aio.service.backoff import Backoff
from tests.service.broker import Broker
from tests.service.conftest import Peer
from tests.service.helpers import (
    astmetad_message,
    astprocd_message,
    eventually,
    longer_than,
    start_event,
)

pytest.importorskip("aiomqtt")


def config_for(broker: Broker, prefix: str = "astoria") -> ServiceConfig:
    return ServiceConfig(host="127.0.0.1", port=broker.port, topic_prefix=prefix)


@pytest.fixture(autouse=True)
def _a_robot_waits(monkeypatch: pytest.MonkeyPatch) -> None:
    """A robot is waiting for the start throughout (the gate itself: test_inbox.py)."""
    monkeypatch.setattr("j5aio.competition.start.is_waiting", lambda: True)


@pytest.fixture
async def service(broker: Broker) -> AsyncIterator[RobotService]:
    async with RobotService(config_for(broker)) as running:
        await running.wait_connected(timeout=10)
        yield running


def zone_is(value: int) -> Callable[[], bool]:
    return lambda: zone() == value


def zone() -> int | None:
    metadata = service_state.metadata()
    return None if metadata is None else metadata.zone


async def test_metadata_arrives_and_updates(service: RobotService, peer: Peer) -> None:
    await peer.publish("astoria/astmetad", astmetad_message(zone=1, mode="COMP"))
    await eventually(lambda: zone() == 1)
    metadata = service_state.metadata()
    assert metadata is not None and metadata.mode is Mode.COMP
    await peer.publish("astoria/astmetad", astmetad_message(zone=3, mode="DEV"))
    await eventually(lambda: zone() == 3)


async def test_retained_metadata_arrives_on_connecting(broker: Broker, peer: Peer) -> None:
    # astmetad's status is retained: a program started later still gets it
    await peer.publish("astoria/astmetad", astmetad_message(zone=2), retain=True)
    async with RobotService(config_for(broker)):
        await eventually(lambda: zone() == 2)


async def test_remote_start_resumes_wait_for_start(service: RobotService, peer: Peer) -> None:
    result: list[str] = []

    async def wait() -> None:
        result.append(await wait_for_start([], timeout=10))

    async with anyio.create_task_group() as group:
        group.start_soon(wait)
        await peer.publish("astoria/broadcast/start_button", start_event())
    assert result == ["remote start"]


async def test_sbot_remote_start(broker: Broker, peer: Peer) -> None:
    starts: list[int] = []
    config = ServiceConfig(host="127.0.0.1", port=broker.port, topic_prefix="sbot/robot")
    async with RobotService(config, start=lambda: starts.append(1)) as running:
        await running.wait_connected(timeout=10)
        await peer.publish("sbot/robot/start_button", {"pressed": False})
        await peer.publish("sbot/robot/start_button", {"pressed": True})
        await eventually(lambda: starts == [1])


async def test_retained_start_does_not_start(broker: Broker, peer: Peer) -> None:
    starts: list[int] = []
    await peer.publish("astoria/broadcast/start_button", start_event(), retain=True)
    async with RobotService(config_for(broker), start=lambda: starts.append(1)) as running:
        await running.wait_connected(timeout=10)
        # a fresh metadata message after the retained start: once it is here, the
        # retained start has been delivered (and ignored) before it
        await peer.publish("astoria/astmetad", astmetad_message(zone=5))
        await eventually(lambda: zone() == 5)
        assert starts == []


async def test_usercode_stick(service: RobotService, peer: Peer) -> None:
    await peer.publish("astoria/astprocd", astprocd_message("/media/usercode"), retain=True)
    await eventually(lambda: service_state.usercode_path() == Path("/media/usercode"))


async def test_bad_payloads_are_ignored_and_logged_once(
    service: RobotService, peer: Peer, caplog: pytest.LogCaptureFixture
) -> None:
    await peer.publish("astoria/astmetad", astmetad_message(zone=4))
    await eventually(lambda: zone() == 4)
    bad: list[bytes | str] = [
        b"\x00garbage",
        b"{" * 10,
        json.dumps(astmetad_message(zone="four")),
        json.dumps(astmetad_message(zone=-1)),
        b" " * 200_000,
    ]
    with caplog.at_level(logging.DEBUG, "j5aio.service"):
        for _ in range(3):
            for payload in bad:
                await peer.publish("astoria/astmetad", payload)
        await peer.publish("astoria/broadcast/start_button", b"[]")
        await peer.publish("astoria/astmetad", astmetad_message(zone=6))
        await eventually(lambda: zone() == 6)
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    # one line per kind of fault: not JSON, wrong metadata, oversized, wrong type
    assert len(warnings) == 4, warnings
    assert any("bytes was ignored" in w for w in warnings)
    assert any("zone" in w for w in warnings)
    assert service.connected


async def test_broker_absent_at_start(tmp_path: Path, broker: Broker) -> None:
    broker.stop()
    starts: list[int] = []
    async with RobotService(
        config_for(broker), start=lambda: starts.append(1), backoff=Backoff(0.05, 0.5)
    ) as running:
        await anyio.sleep(0.3)  # a few failed attempts; the program goes on meanwhile
        assert not running.connected
        broker.start()
        await running.wait_connected(timeout=10)
        aiomqtt = pytest.importorskip("aiomqtt")
        async with aiomqtt.Client("127.0.0.1", broker.port) as client:
            await Peer(client).publish("astoria/broadcast/start_button", start_event())
        await eventually(lambda: starts == [1])


async def test_broker_killed_and_restarted(
    broker: Broker, caplog: pytest.LogCaptureFixture
) -> None:
    aiomqtt = pytest.importorskip("aiomqtt")
    starts: list[int] = []
    with caplog.at_level(logging.INFO, "j5aio.service"):
        async with RobotService(config_for(broker), start=lambda: starts.append(1)) as svc:
            await svc.wait_connected(timeout=10)
            async with aiomqtt.Client("127.0.0.1", broker.port) as client:
                await Peer(client).publish("astoria/astmetad", astmetad_message(zone=1))
            await eventually(lambda: zone() == 1)
            for round_ in range(2):
                broker.stop()
                await eventually(lambda: not svc.connected)
                # the last good metadata stays while the broker is away
                assert zone() == 1 + round_
                broker.start()
                await svc.wait_connected(timeout=10)
                async with aiomqtt.Client("127.0.0.1", broker.port) as client:
                    peer = Peer(client)
                    await peer.publish("astoria/broadcast/start_button", start_event())
                    await peer.publish("astoria/astmetad", astmetad_message(zone=2 + round_))
                await eventually(longer_than(starts, round_))
                await eventually(zone_is(2 + round_))
            assert svc.link.connections == 3
    lost = [r for r in caplog.records if "lost the broker" in r.getMessage()]
    assert lost and all(r.levelno == logging.WARNING for r in lost)


async def test_frames_are_published_and_rate_limited(broker: Broker) -> None:
    aiomqtt = pytest.importorskip("aiomqtt")
    jpeg = b"\xff\xd8\xff\xe0fake jpeg\xff\xd9"
    received: list[dict[str, object]] = []
    async with aiomqtt.Client("127.0.0.1", broker.port) as watcher:
        await watcher.subscribe("camera/annotated", qos=1)

        async def watch() -> None:
            async for message in watcher.messages:
                assert isinstance(message.payload, bytes)
                received.append(json.loads(message.payload))

        async with anyio.create_task_group() as group:
            group.start_soon(watch)
            assert not publish_frame(jpeg)  # no service: dropped
            async with RobotService(config_for(broker), max_frame_rate=1.0) as svc:
                await svc.wait_connected(timeout=10)
                assert current_service() is svc
                taken = [publish_frame(jpeg) for _ in range(50)]
                assert taken[0] and taken.count(True) == 1  # the rest came too soon
                await eventually(lambda: len(received) == 1)
                await eventually(lambda: publish_frame(jpeg))  # after a second
                await eventually(lambda: len(received) == 2)
                assert svc.frames.sent == 2 and svc.frames.dropped >= 49
            assert current_service() is None
            group.cancel_scope.cancel()
    frame = received[0]
    assert isinstance(frame["timestamp"], float)
    assert frame["data"] == "data:image/jpeg;base64, /9j/4GZha2UganBlZ//Z"


async def test_stop_is_prompt_and_repeatable(broker: Broker) -> None:
    svc = RobotService(config_for(broker))
    await svc.stop()  # never started: nothing to do
    await svc.start()
    assert svc.running
    with pytest.raises(RuntimeError, match="running already"):
        await svc.start()
    await svc.wait_connected(timeout=10)
    with anyio.fail_after(10):
        await svc.stop()
    assert not svc.running and not svc.connected
    await svc.stop()


@pytest.mark.parametrize("v311", [False, True])
async def test_start_service_returns_with_the_retained_state(
    broker: Broker, peer: Peer, v311: bool
) -> None:
    from j5aio.service import start_service

    await peer.publish("astoria/astmetad", astmetad_message(zone=7), retain=True)
    await peer.publish("astoria/astprocd", astprocd_message("/media/team"), retain=True)
    config = ServiceConfig(host="127.0.0.1", port=broker.port, mqtt_v311=v311)
    service = await start_service(config, settle=30)
    assert service is not None
    try:
        # no waiting here: start_service returned once the retained messages were handled
        assert zone() == 7
        assert service_state.usercode_path() == Path("/media/team")
    finally:
        await service.stop()


async def test_start_service_does_not_wait_for_an_absent_broker(broker: Broker) -> None:
    from j5aio.service import start_service

    broker.stop()
    with anyio.fail_after(20):  # it would wait the whole 30 s for a broker it waited for
        service = await start_service(config_for(broker), settle=30)
    assert service is not None
    try:
        assert not service.connected  # returned after the first failed attempt
    finally:
        await service.stop()
