"""Fixtures for the robot service's tests: a real broker, a peer client, clean state."""

from __future__ import annotations

import json
from collections.abc import AsyncIterator, Iterator

import pytest

from j5aio.competition import service_state
from j5aio.competition.start import clear_trigger
from tests.service.broker import MOSQUITTO, Broker, start_broker


@pytest.fixture(autouse=True)
def _clean_service_state() -> Iterator[None]:
    service_state.clear()
    clear_trigger()
    yield
    service_state.clear()
    clear_trigger()


@pytest.fixture
def broker() -> Iterator[Broker]:
    """A mosquitto broker of its own on a free port of 127.0.0.1, killed afterwards."""
    if MOSQUITTO is None:
        pytest.skip(
            "mosquitto is not installed (Debian: apt-get install mosquitto; .ci/run "
            "installs it): the robot service's tests need a real broker"
        )
    try:
        running, directory = start_broker()
    except (OSError, RuntimeError) as exc:
        pytest.skip(f"mosquitto cannot run here: {exc}")
    try:
        yield running
    finally:
        running.stop()
        directory.cleanup()


class Peer:
    """The service's side: publishes astoria's and sbot's messages on the broker."""

    def __init__(self, client: object) -> None:
        self.client = client

    async def publish(
        self, topic: str, payload: bytes | str | dict[str, object], retain: bool = False
    ) -> None:
        if isinstance(payload, dict):
            payload = json.dumps(payload)
        await self.client.publish(topic, payload, qos=1, retain=retain)  # type: ignore[attr-defined]


@pytest.fixture
async def peer(broker: Broker) -> AsyncIterator[Peer]:
    aiomqtt = pytest.importorskip("aiomqtt")
    async with aiomqtt.Client("127.0.0.1", broker.port, identifier=None) as client:
        yield Peer(client)
