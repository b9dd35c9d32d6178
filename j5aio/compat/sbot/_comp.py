"""sbot's ``comp``: the match's zone and mode, known once the robot has started."""

from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict

from .internal.exceptions import MetadataNotReadyError

if TYPE_CHECKING:
    from j5aio.sync import KitRobot

__all__ = ["DEFAULT_METADATA", "METADATA_ENV_VAR", "METADATA_NAME", "Comp", "Metadata"]

#: The environment variable naming the folder sbot searches for the metadata file.
METADATA_ENV_VAR = "SBOT_METADATA_PATH"
#: The name of sbot's metadata file.
METADATA_NAME = "metadata.json"


class Metadata(TypedDict):
    """The metadata sbot gives: whether this is a match, and the starting zone."""

    is_competition: bool
    zone: int


#: The metadata when no match is being played.
DEFAULT_METADATA: Metadata = {"is_competition": False, "zone": 0}


class Comp:
    """The match's metadata: read from j5aio's robot when the start is pressed."""

    def __init__(self) -> None:
        self._metadata: Metadata | None = None

    @property
    def is_competition(self) -> bool:
        """Whether the robot is in a match.

        :raises MetadataNotReadyError: the robot has not started yet.
        """
        if self._metadata is None:
            raise MetadataNotReadyError()
        return self._metadata["is_competition"]

    @property
    def zone(self) -> int:
        """The zone the robot starts in.

        :raises MetadataNotReadyError: the robot has not started yet.
        """
        if self._metadata is None:
            raise MetadataNotReadyError()
        return self._metadata["zone"]

    @property
    def loaded(self) -> bool:
        """Whether the metadata has been read (the robot has started)."""
        return self._metadata is not None

    def _load(self, robot: KitRobot) -> None:
        """Take the metadata j5aio's robot read at the start."""
        metadata = robot.metadata
        self._metadata = {"is_competition": metadata.is_competition, "zone": metadata.zone}
