"""The robot's service client: its lifetime, and the functions a robot calls.

A robot starts it in its setup with :func:`~j5aio.service.auto.start_service` and stops
it when it closes::

    service = await start_service()  # None where no service is configured
    ...
    if service is not None:
        await service.stop()

or, in a program of its own, ``async with RobotService(config):``. While it runs, in a
background task on the event loop that started it:

- astoria's metadata goes to :func:`j5aio.competition.service_state.set_metadata` (and
  follows every update), the team's stick to
  :func:`~j5aio.competition.service_state.set_usercode_path`;
- a remote start calls :func:`~j5aio.competition.start.trigger_start` with
  ``"remote start"``;
- :func:`publish_frame` sends camera frames to the robot's web page.

Nothing the broker does (absent, killed, restarted, bad messages) stops, slows or
starts the program: it is logged once and retried in the background.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from types import TracebackType
from typing import Any, Self

import anyio

from j5aio.service._extra import require_aiomqtt
from j5aio.service.backoff import Backoff
from j5aio.service.config import ServiceConfig
from j5aio.service.connection import Link, make_client, stay_connected
from j5aio.service.frames import DEFAULT_MAX_RATE, FrameLike, FramePublisher
from j5aio.service.inbox import Inbox
from j5aio.service.messages import Topics

__all__ = ["RobotService", "current_service", "publish_frame"]

LOGGER = logging.getLogger(__name__)

_current: RobotService | None = None


class RobotService:
    """A client of the robot's service (astoria, over MQTT) for this program.

    :param config: where the broker is (:func:`~j5aio.service.config.find_config`).
    :param max_frame_rate: camera frames a second sent at most.
    :param start: called for a remote start, on the event loop; by default
        :func:`~j5aio.competition.start.trigger_start` with ``"remote start"``.
    :param backoff: the delays between attempts to reach the broker.
    :param client_factory: makes the MQTT client for each attempt
        (:func:`~j5aio.service.connection.make_client`; tests give fakes).
    :raises ~j5aio.service.ServiceNotInstalledError: aiomqtt is not installed.
    """

    def __init__(
        self,
        config: ServiceConfig,
        *,
        max_frame_rate: float = DEFAULT_MAX_RATE,
        start: Callable[[], None] | None = None,
        backoff: Backoff | None = None,
        client_factory: Callable[[ServiceConfig], Any] = make_client,
    ) -> None:
        require_aiomqtt()
        self.config = config
        self.topics = Topics.for_config(config)
        self.inbox = Inbox(self.topics, start)
        self.link = Link()
        self.frames = FramePublisher(max_frame_rate)
        self._backoff = backoff
        self._client_factory = client_factory
        self._scope: anyio.CancelScope | None = None
        self._task: asyncio.Task[None] | None = None

    @property
    def running(self) -> bool:
        """Whether :meth:`start` has been called and :meth:`stop` not yet."""
        return self._task is not None

    @property
    def connected(self) -> bool:
        """Whether the broker is connected now."""
        return self.link.connected

    async def wait_connected(self, timeout: float | None = None) -> None:
        """Wait until the broker is connected (a start-up that needs the service).

        :raises TimeoutError: it did not connect within ``timeout`` seconds.
        """
        with anyio.fail_after(timeout):
            await self.link.wait_connected()

    async def wait_settled(self, timeout: float = 0.5) -> None:
        """Wait, at most ``timeout`` seconds, for what the service said before the start.

        Returns once the first attempt to reach the broker has failed (an absent broker
        costs nothing), or has succeeded and the broker's retained messages (astoria's
        metadata and stick) have been handled.
        """
        with anyio.move_on_after(timeout):
            await self.link.wait_ready()

    async def start(self) -> None:
        """Start talking to the service in a background task; returns at once.

        The broker need not be there: the task keeps trying.

        :raises RuntimeError: it is running already.
        """
        global _current
        if self._task is not None:
            raise RuntimeError("this robot service is running already")
        scope = anyio.CancelScope()
        self._scope = scope
        self._task = asyncio.get_running_loop().create_task(
            self._run(scope), name="j5aio robot service"
        )
        _current = self

    async def stop(self) -> None:
        """Stop talking to the service and wait for its task to end (safe to repeat)."""
        global _current
        task, scope = self._task, self._scope
        self._task = self._scope = None
        if _current is self:
            _current = None
        if task is None or scope is None:
            return
        scope.cancel()
        with anyio.CancelScope(shield=True):
            await asyncio.wait([task])
        if not task.cancelled() and task.exception() is not None:
            LOGGER.error("Robot service: its task failed", exc_info=task.exception())

    async def _run(self, scope: anyio.CancelScope) -> None:
        with scope:
            async with anyio.create_task_group() as group:
                group.start_soon(self.frames.run, self._send_frame)
                await stay_connected(
                    self.config,
                    self.inbox,
                    self.link,
                    backoff=self._backoff,
                    client_factory=self._client_factory,
                )

    async def _send_frame(self, message: bytes) -> None:
        await self.link.publish(self.topics.frames, message)

    def publish_frame(self, frame: FrameLike) -> bool:
        """Offer a camera frame to the robot's web page (see :func:`publish_frame`)."""
        return self.frames.offer(frame)

    async def __aenter__(self) -> Self:
        await self.start()
        return self

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        await self.stop()


def current_service() -> RobotService | None:
    """The service started last in this process and not stopped, or ``None``."""
    return _current


def publish_frame(frame: FrameLike) -> bool:
    """Offer an annotated camera frame to the robot's web page; from any thread.

    It costs the caller next to nothing and never blocks: the frame is taken only when
    the service is running, the previous frame has gone, and the rate allows it
    (otherwise it is dropped), then encoded in a worker thread and published.

    :param frame: a BGR or greyscale picture (a numpy array that is not changed
        afterwards), the bytes of a JPEG, or a call that makes either (it runs only for
        a frame that is taken, on the encoding thread: the place for the annotation).
    :returns: whether the frame was taken.
    """
    service = _current
    return service is not None and service.publish_frame(frame)
