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

__all__ = ["REMOTE_START", "Inbox"]

LOGGER = logging.getLogger(__name__)

#: What :func:`~j5aio.competition.start.wait_for_start` reports a remote start as.
REMOTE_START = "remote start"


def _trigger_remote_start() -> None:
    from j5aio.competition.start import trigger_start

    trigger_start(REMOTE_START)


class Inbox:
    """Reads each message from the broker and passes on what it means.

    :param topics: the topics in use.
    :param start: called for a remote start (it must be safe to call on the event loop);
        :func:`~j5aio.competition.start.trigger_start` by default.
    """

    def __init__(self, topics: Topics, start: Callable[[], None] | None = None) -> None:
        self.topics = topics
        self._start = start or _trigger_remote_start
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
        self.starts += 1
        self._start()
