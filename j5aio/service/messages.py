"""What the service's messages mean: astoria 0.11's and sbot 2026's topics and payloads.

Every topic is under the configuration's prefix (``astoria`` on SR's robots):

- ``astmetad``: astoria's metadata manager, a retained status message
  ``{"status": "RUNNING" | "STOPPED", "astoria_version": ..., "metadata": {...}}`` whose
  ``metadata`` has ``arena``, ``zone``, ``mode``, ``marker_offset``, ``game_timeout``,
  ``wifi_enabled`` and facts about the robot's software. Only a RUNNING message carries
  metadata to believe;
- ``astprocd``: astoria's process manager, a retained status message with
  ``code_status``, ``pid`` and ``disk_info`` ``{"uuid", "mount_path", "disk_type"}``: the
  team's USB stick, when the status is RUNNING and there is one;
- ``broadcast/start_button``: astoria's remote start, ``{"event_name": "start_button",
  "sender_name": ..., "priority": 0}``, sent (never retained) by the robot's web page or
  ``astctl usercode trigger``;
- ``start_button``: sbot's remote start, ``{"pressed": true}``.

The functions here only read: :class:`~j5aio.service.inbox.Inbox` acts on what they say.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from j5aio.service.payloads import PayloadError, optional_field, require_field

if TYPE_CHECKING:
    from j5aio.competition.metadata import Metadata
    from j5aio.service.config import ServiceConfig

__all__ = [
    "Topics",
    "read_astoria_start",
    "read_metadata_message",
    "read_process_message",
    "read_sbot_start",
]

_RUNNING = "RUNNING"
_STATUSES = ("RUNNING", "STOPPED")
_MAX_PATH_LENGTH = 4096


@dataclass(frozen=True)
class Topics:
    """The whole topics the service listens to and publishes on."""

    #: astoria's metadata manager's status.
    metadata: str
    #: astoria's process manager's status (the usercode stick).
    process: str
    #: astoria's remote start broadcast.
    start: str
    #: sbot's remote start.
    sbot_start: str
    #: where annotated camera frames go.
    frames: str

    @classmethod
    def for_config(cls, config: ServiceConfig) -> Topics:
        """The topics under ``config``'s prefix."""
        return cls(
            metadata=config.topic("astmetad"),
            process=config.topic("astprocd"),
            start=config.topic("broadcast/start_button"),
            sbot_start=config.topic("start_button"),
            frames=config.frame_topic,
        )

    @property
    def subscriptions(self) -> tuple[str, ...]:
        """The topics to subscribe to."""
        return (self.metadata, self.process, self.start, self.sbot_start)


def _status(data: Mapping[str, object], topic: str) -> str:
    status = require_field(data, "status", str, topic)
    if status not in _STATUSES:
        raise PayloadError(
            "wrong type",
            f"{topic}: a message whose status is {status!r} was ignored "
            f"(it must be one of {', '.join(_STATUSES)})",
        )
    assert isinstance(status, str)
    return status


def read_metadata_message(data: Mapping[str, object], topic: str) -> Metadata | None:
    """The metadata in an ``astmetad`` status message; ``None`` if astmetad is stopped.

    :raises PayloadError: the message or its metadata is malformed (the metadata's
        fields are checked by :func:`~j5aio.competition.metadata.parse_astoria_metadata`).
    """
    from j5aio.competition.metadata import MetadataError, parse_astoria_metadata

    if _status(data, topic) != _RUNNING:
        return None
    fields = require_field(data, "metadata", dict, topic)
    try:
        return parse_astoria_metadata(fields, f"the {topic} message")
    except MetadataError as exc:
        raise PayloadError("bad metadata", f"{exc}; the message was ignored") from None


def read_process_message(data: Mapping[str, object], topic: str) -> Path | None:
    """Where the team's USB stick is mounted, from an ``astprocd`` status message.

    :returns: ``None`` when astprocd is stopped or names no stick.
    :raises PayloadError: the message is malformed.
    """
    if _status(data, topic) != _RUNNING:
        return None
    disk = optional_field(data, "disk_info", dict, topic)
    if disk is None:
        return None
    assert isinstance(disk, dict)
    where = f"{topic} disk_info"
    mount_path = require_field(disk, "mount_path", str, where)
    assert isinstance(mount_path, str)
    if not mount_path.startswith("/") or "\0" in mount_path or (
        len(mount_path) > _MAX_PATH_LENGTH
    ):
        raise PayloadError(
            "wrong type",
            f"{where}: a mount_path that is not an absolute path ({mount_path[:80]!r}) "
            "was ignored",
        )
    return Path(mount_path)


def read_astoria_start(data: Mapping[str, object], topic: str) -> str:
    """Check an astoria ``start_button`` broadcast event; return who sent it.

    :raises PayloadError: it lacks ``event_name`` or ``sender_name`` (text), or its
        ``priority`` is not a whole number.
    """
    require_field(data, "event_name", str, topic)
    sender = require_field(data, "sender_name", str, topic)
    optional_field(data, "priority", int, topic)
    assert isinstance(sender, str)
    return sender


def read_sbot_start(data: Mapping[str, object], topic: str) -> bool:
    """Whether an sbot ``start_button`` message says the button is pressed.

    :raises PayloadError: it has no ``pressed``, or ``pressed`` is not true or false.
    """
    pressed = require_field(data, "pressed", bool, topic)
    return pressed is True
