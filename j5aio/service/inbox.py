"""Acting on the service's messages: metadata, the stick's path, remote starts.

Metadata and the stick's path go to the competition layer's
:mod:`~j5aio.competition.service_state`, remote starts to the start.

A message that is oversized, not JSON or wrongly typed is ignored and logged (each kind
once per topic); the last good metadata and path stay as they were.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from pathlib import Path

from j5aio.competition import service_state
from j5aio.service.faults import FaultLog
from j5aio.service.messages import (
    Topics,
    read_astoria_start,
    read_metadata_message,
    read_process_message,
    read_sbot_start,
)
from j5aio.service.payloads import PayloadError, decode_object

__all__ = ["REMOTE_START", "Inbox", "robot_is_waiting"]

LOGGER = logging.getLogger(__name__)

#: What :func:`~j5aio.competition.start.wait_for_start` reports a remote start as.
REMOTE_START = "remote start"


def _trigger_remote_start() -> None:
    from j5aio.competition.start import trigger_start

    trigger_start(REMOTE_START)


def robot_is_waiting() -> bool:
    """Whether a robot in this process is waiting for the start now.

    (:func:`j5aio.competition.start.is_waiting`: a remote start counts only then.)
    """
    from j5aio.competition.start import is_waiting

    return is_waiting()


class Inbox:
    """Reads each message from the broker and passes on what it means.

    :param topics: the topics in use.
    :param start: called for a remote start (it must be safe to call on the event loop);
        :func:`~j5aio.competition.start.trigger_start` by default.
    :param waiting: says whether the robot is waiting for the start
        (:func:`~j5aio.service.inbox.robot_is_waiting` by default). As on astoria's
        robots, only a remote start that arrives while the robot waits counts: one sent
        before is stale.
    """

    def __init__(
        self,
        topics: Topics,
        start: Callable[[], None] | None = None,
        waiting: Callable[[], bool] | None = None,
    ) -> None:
        self.topics = topics
        self._start = start or _trigger_remote_start
        self._waiting = waiting or robot_is_waiting
        self.faults = FaultLog(LOGGER)
        #: How many remote starts have been passed on.
        self.starts = 0

    def receive(self, topic: str, payload: bytes | bytearray | str, retained: bool) -> None:
        """Act on one message. Never raises for a bad message: it is logged and ignored.

        :param topic: the topic it came on.
        :param payload: its bytes.
        :param retained: whether the broker kept it from before (a retained remote start
            is stale and never starts the robot).
        """
        try:
            self._receive(topic, payload, retained)
        except PayloadError as exc:
            self.faults.report((exc.kind, topic), "Robot service: %s", exc)
        except Exception:  # a fault of ours must not end the service's task either
            if self.faults.report(("failed", topic), "Robot service: a message on %s "
                                  "could not be handled", topic):
                LOGGER.exception("Robot service: handling a message on %s failed", topic)

    def _receive(self, topic: str, payload: bytes | bytearray | str, retained: bool) -> None:
        topics = self.topics
        if topic not in topics.subscriptions:
            LOGGER.debug("Robot service: ignoring a message on %s", topic)
            return
        if topic in (topics.start, topics.sbot_start) and retained:
            LOGGER.info("Robot service: ignoring a remote start kept from before (%s)", topic)
            return
        data = decode_object(payload, topic)
        if topic == topics.metadata:
            metadata = read_metadata_message(data, topic)
            if metadata is None:
                LOGGER.info("Robot service: astmetad is stopped; keeping the last metadata")
                return
            LOGGER.debug("Robot service: metadata %s", metadata)
            service_state.set_metadata(metadata)
        elif topic == topics.process:
            path: Path | None = read_process_message(data, topic)
            if path is not None:
                service_state.set_usercode_path(path)
        elif topic == topics.start:
            sender = read_astoria_start(data, topic)
            LOGGER.info("Robot service: remote start from %s", sender)
            self._remote_start()
        elif read_sbot_start(data, topic):
            LOGGER.info("Robot service: remote start (sbot)")
            self._remote_start()

    def _remote_start(self) -> None:
        if not self._waiting():
            LOGGER.info("Robot service: the robot is not waiting for the start: the remote "
                        "start was ignored")
            return
        self.starts += 1
        self._start()
