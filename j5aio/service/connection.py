"""Staying connected to the broker: connect, subscribe, read, and after any failure retry.

:func:`stay_connected` never returns and never raises for the broker's sake: a broker
absent at the start, killed, or restarted is retried with :class:`~.backoff.Backoff`
(every second at most once it has been away a while, so the service is back within
about a second of the broker's return), and the failure is logged once until the
connection comes back.
"""

from __future__ import annotations

import asyncio
import logging
import os
import ssl
import uuid
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Final

import anyio

from j5aio.service._extra import require_aiomqtt
from j5aio.service.backoff import Backoff
from j5aio.service.faults import FaultLog

if TYPE_CHECKING:
    from j5aio.service.config import ServiceConfig
    from j5aio.service.inbox import Inbox

__all__ = ["CONNECT_TIMEOUT", "KEEPALIVE", "Link", "make_client", "stay_connected"]

LOGGER = logging.getLogger(__name__)

#: Seconds to wait for the broker to accept a connection.
CONNECT_TIMEOUT: Final = 10.0
#: Seconds of silence after which the client pings the broker (a broker that vanished
#: without closing the connection is noticed within one and a half times this).
KEEPALIVE: Final = 5
#: Messages held for the inbox at most; beyond, the broker is slowed (not the program).
_MAX_QUEUED: Final = 256
#: Seconds allowed for a goodbye to the broker.
_CLOSE_TIMEOUT: Final = 2.0


class Link:
    """The connection of the moment, for publishing; ``None`` between connections."""

    def __init__(self) -> None:
        self.client: Any = None
        #: How many times a connection has been made.
        self.connections = 0
        # asyncio's events: they may be made outside the loop that waits on them
        self._connected = asyncio.Event()
        self._ready = asyncio.Event()

    @property
    def connected(self) -> bool:
        """Whether the broker is connected now."""
        return self.client is not None

    async def wait_connected(self) -> None:
        """Wait until the broker is connected (at once if it is)."""
        if self.client is None:
            await self._connected.wait()

    async def wait_ready(self) -> None:
        """Wait until the first attempt to connect has ended.

        That is: it has failed, or it has succeeded and the broker's retained messages
        (what the service said before) have been handled.
        """
        await self._ready.wait()

    def ready(self) -> None:
        """Record that :meth:`wait_ready` need wait no more."""
        self._ready.set()

    def attach(self, client: Any) -> None:
        """Record a new connection."""
        self.client = client
        self.connections += 1
        self._connected.set()

    def detach(self) -> None:
        """Record that the connection has ended."""
        self.client = None
        self._connected.clear()

    async def publish(self, topic: str, payload: bytes) -> None:
        """Publish with QoS 1, as astoria's peers do.

        :raises ConnectionError: the broker is not connected.
        """
        client = self.client
        if client is None:
            raise ConnectionError("the broker is not connected")
        await client.publish(topic, payload, qos=1)


def _identifier() -> str:
    # Unique: two programs (or a test beside a robot) must not knock each other off.
    return f"j5aio-{os.getpid()}-{uuid.uuid4().hex[:8]}"


def make_client(config: ServiceConfig) -> Any:
    """An ``aiomqtt.Client`` for ``config`` (not connected yet).

    :raises ~j5aio.service.ServiceNotInstalledError: aiomqtt is not installed.
    """
    aiomqtt = require_aiomqtt()
    return aiomqtt.Client(
        config.host,
        config.port,
        username=config.username,
        password=config.password,
        identifier=_identifier(),
        protocol=aiomqtt.ProtocolVersion.V311 if config.mqtt_v311 else aiomqtt.ProtocolVersion.V5,
        tls_context=ssl.create_default_context() if config.tls else None,
        timeout=CONNECT_TIMEOUT,
        keepalive=KEEPALIVE,
        max_queued_incoming_messages=_MAX_QUEUED,
    )


def _payload(value: object) -> bytes | str:
    if isinstance(value, bytes | str):
        return value
    if isinstance(value, bytearray):
        return bytes(value)
    return "" if value is None else str(value)


async def _serve(
    client: Any, inbox: Inbox, link: Link, backoff: Backoff, faults: FaultLog, where: str
) -> None:
    """Subscribe, then hand every message to ``inbox`` until the connection fails."""
    for topic in inbox.topics.subscriptions:
        await client.subscribe(topic, qos=1)
    # One more round trip: the broker answers it after sending the retained messages of
    # the subscriptions above, so they are all queued by the time it returns.
    await client.unsubscribe(inbox.topics.metadata + "/j5aio-settle")
    retained = len(client.messages)
    link.attach(client)
    backoff.reset()
    if faults.seen("lost"):
        LOGGER.warning("Robot service: connected again to the broker at %s", where)
    else:
        LOGGER.info("Robot service: connected to the broker at %s", where)
    faults.forget("lost")
    if not retained:
        link.ready()
    async for message in client.messages:
        inbox.receive(str(message.topic), _payload(message.payload), message.retain)
        retained -= 1
        if retained == 0:
            link.ready()


async def _close(client: Any, mqtt_error: type[Exception]) -> None:
    """Say goodbye to the broker, even when cancelled (else the socket is left open)."""
    with anyio.CancelScope(shield=True), anyio.move_on_after(_CLOSE_TIMEOUT):
        try:
            await client.__aexit__(None, None, None)
        except (mqtt_error, OSError) as exc:
            LOGGER.debug("Robot service: closing the connection: %r", exc)


async def stay_connected(
    config: ServiceConfig,
    inbox: Inbox,
    link: Link,
    *,
    backoff: Backoff | None = None,
    client_factory: Callable[[ServiceConfig], Any] = make_client,
) -> None:
    """Keep a connection to the broker, feeding every message to ``inbox``, until cancelled.

    :param config: where the broker is.
    :param inbox: acts on the messages.
    :param link: set to each connection while it lasts.
    :param backoff: the delays between attempts.
    :param client_factory: makes a client (for tests).
    """
    aiomqtt = require_aiomqtt()
    backoff = backoff or Backoff()
    faults = FaultLog(LOGGER)
    where = f"{config.host}:{config.port}"
    while True:
        client = client_factory(config)
        try:
            await client.__aenter__()
        except anyio.get_cancelled_exc_class():
            await _close(client, aiomqtt.MqttError)  # cancelled half way: close the socket
            raise
        except (aiomqtt.MqttError, OSError) as exc:
            link.ready()
            faults.report(
                "lost", "Robot service: cannot reach the broker at %s (%s); retrying in "
                "the background", where, exc,
            )
        else:
            try:
                await _serve(client, inbox, link, backoff, faults, where)
            except (aiomqtt.MqttError, OSError) as exc:
                faults.report(
                    "lost", "Robot service: lost the broker at %s (%s); retrying in the "
                    "background", where, exc,
                )
            finally:
                link.detach()
                await _close(client, aiomqtt.MqttError)
        await anyio.sleep(backoff.next())
