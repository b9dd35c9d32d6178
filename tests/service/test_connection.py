"""The connection's edges, with fake clients where a real broker cannot make them happen."""

from __future__ import annotations

import logging
from types import TracebackType

import anyio
import pytest

from j5aio.service import RobotService, ServiceConfig
from j5aio.service.config import ServiceConfig as Config
from j5aio.service.connection import Link, _close, _payload

pytest.importorskip("aiomqtt")


def test_payloads_of_every_type_become_bytes_or_text() -> None:
    assert _payload(b"x") == b"x"
    assert _payload("x") == "x"
    assert _payload(bytearray(b"x")) == b"x"
    assert _payload(None) == ""
    assert _payload(12) == "12"


async def test_publishing_without_a_connection_is_an_error() -> None:
    link = Link()
    with pytest.raises(ConnectionError, match="not connected"):
        await link.publish("camera/annotated", b"{}")


class FailingGoodbye:
    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        raise OSError("socket already closed")


async def test_a_failed_goodbye_is_only_noted(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.DEBUG, "j5aio.service"):
        await _close(FailingGoodbye(), RuntimeError)
    assert "socket already closed" in caplog.text


async def test_a_bug_in_the_client_ends_the_task_and_is_logged(
    caplog: pytest.LogCaptureFixture,
) -> None:
    def broken_factory(config: Config) -> object:
        raise RuntimeError("a bug")

    service = RobotService(ServiceConfig(host="127.0.0.1", port=1), client_factory=broken_factory)
    await service.start()
    await anyio.sleep(0.05)
    with caplog.at_level(logging.ERROR, "j5aio.service"):
        await service.stop()
    assert "its task failed" in caplog.text and "a bug" in caplog.text


class SlowToConnect:
    """A client whose broker never answers the connection."""

    def __init__(self) -> None:
        self.closed = False
        self.entered = anyio.Event()

    async def __aenter__(self) -> SlowToConnect:
        self.entered.set()
        await anyio.sleep_forever()
        raise AssertionError("unreachable")

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.closed = True


async def test_stopping_while_connecting_closes_the_half_made_connection() -> None:
    clients: list[SlowToConnect] = []

    def factory(config: Config) -> SlowToConnect:
        clients.append(SlowToConnect())
        return clients[-1]

    service = RobotService(ServiceConfig(host="127.0.0.1", port=1), client_factory=factory)
    await service.start()
    with anyio.fail_after(10):
        while not clients:  # noqa: ASYNC110 - the service's task makes it
            await anyio.sleep(0.01)
        await clients[0].entered.wait()
        await service.stop()
    assert clients[0].closed and not service.running
