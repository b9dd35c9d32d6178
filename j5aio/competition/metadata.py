"""Match metadata: which arena and zone the robot starts in, and whether this is a match.

On match day the competition hands each robot a USB stick with a ``metadata.json`` file
at its top level, for example::

    {"arena": "A", "zone": 2, "mode": "COMP", "duration": 150, "marker_offset": 0}

:func:`load_metadata` looks for the file, in order:

1. at the path in the ``J5AIO_METADATA`` environment variable (it must exist then);
2. at the top of every mounted removable drive (on Linux the mount points one or two
   levels below ``/media`` and ``/run/media``; ``J5AIO_MEDIA_ROOTS`` replaces that list,
   separated by ``os.pathsep``);
3. nowhere: then it is the development defaults, :data:`DEV_DEFAULTS`.

A malformed file or a bad field is a :class:`MetadataError` naming the file, the field
and what is allowed. In COMP mode every field must be given: nothing is filled in.
"""

from __future__ import annotations

import logging
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path
from typing import Final

__all__ = [
    "DEFAULT_MEDIA_ROOTS",
    "DEV_DEFAULTS",
    "MAX_DURATION",
    "MAX_MARKER_OFFSET",
    "MAX_ZONE",
    "MEDIA_ROOTS_VARIABLE",
    "METADATA_FILENAME",
    "METADATA_VARIABLE",
    "Metadata",
    "MetadataError",
    "Mode",
    "find_metadata_file",
    "find_usb_sticks",
    "load_metadata",
    "parse_astoria_metadata",
    "parse_metadata",
]

LOGGER = logging.getLogger(__name__)

#: The file's name at the top of a USB stick.
METADATA_FILENAME: Final = "metadata.json"
#: An environment variable naming the metadata file to use (it wins over any stick).
METADATA_VARIABLE: Final = "J5AIO_METADATA"
#: An environment variable replacing :data:`DEFAULT_MEDIA_ROOTS` (``os.pathsep``-separated).
MEDIA_ROOTS_VARIABLE: Final = "J5AIO_MEDIA_ROOTS"
#: Where removable drives are mounted on Linux (``/media/STICK``, ``/media/USER/STICK``,
#: ``/run/media/USER/STICK``).
DEFAULT_MEDIA_ROOTS: Final = (Path("/media"), Path("/run/media"))
#: The highest zone number allowed.
MAX_ZONE: Final = 99
#: The longest match allowed, in seconds (an hour).
MAX_DURATION: Final = 3600.0
#: The highest marker offset allowed.
MAX_MARKER_OFFSET: Final = 10_000
_MAX_ARENA_LENGTH: Final = 32
_MAX_FILE_BYTES: Final = 64 * 1024


class Mode(StrEnum):
    """Whether the robot is in a match (``COMP``) or being developed (``DEV``).

    Each compares equal to (and prints as) its name: ``robot.mode == "COMP"``.
    """

    #: In a match: the start signal comes from the arena and the match is timed.
    COMP = "COMP"
    #: Being developed: no arena, no match timer.
    DEV = "DEV"


class MetadataError(ValueError):
    """The metadata file is unreadable, malformed, or has a bad field."""


@dataclass(frozen=True)
class Metadata:
    """The settings of a match, or of development at the bench.

    :param arena: the arena's name (1 to 32 characters, e.g. ``"A"``).
    :param zone: the starting zone, 0 to :data:`MAX_ZONE`.
    :param mode: :attr:`~j5aio.competition.metadata.Mode.COMP` in a match,
        :attr:`~j5aio.competition.metadata.Mode.DEV` otherwise.
    :param duration: the match's length in seconds (more than 0, at most an hour), or
        ``None`` for no time limit.
    :param marker_offset: added to marker numbers in this arena (0 or more).
    :param source: the file this came from; ``None`` for the defaults.
    :param wifi_enabled: whether the robot's WiFi hotspot is allowed (astoria's
        ``wifi_enabled``), or ``None`` where the format does not say.
    :raises MetadataError: a field is out of range or of the wrong type.
    """

    arena: str = "A"
    zone: int = 0
    mode: Mode = Mode.DEV
    duration: float | None = None
    marker_offset: int = 0
    source: Path | None = None
    wifi_enabled: bool | None = None
    origin: str | None = None

    def __post_init__(self) -> None:
        where = str(self.source or self.origin or "metadata")
        _check_arena(self.arena, where)
        _check_int(self.zone, "zone", where, 0, MAX_ZONE)
        if not isinstance(self.mode, Mode):
            raise MetadataError(f"{where}: mode must be a Mode, not {self.mode!r}")
        if self.duration is not None:
            _check_duration(self.duration, where)
        _check_int(self.marker_offset, "marker_offset", where, 0, MAX_MARKER_OFFSET)
        if self.wifi_enabled is not None and not isinstance(self.wifi_enabled, bool):
            raise MetadataError(
                f"{where}: field 'wifi_enabled' must be true, false or null, "
                f"not {self.wifi_enabled!r}"
            )

    @property
    def is_competition(self) -> bool:
        """Whether this is a match (COMP mode)."""
        return self.mode is Mode.COMP


def _check_arena(value: object, where: str) -> None:
    if not isinstance(value, str) or not 1 <= len(value) <= _MAX_ARENA_LENGTH:
        raise MetadataError(
            f"{where}: field 'arena' must be a string of 1 to {_MAX_ARENA_LENGTH} "
            f"characters, not {value!r}"
        )
    if not value.isprintable() or value != value.strip():
        raise MetadataError(
            f"{where}: field 'arena' must be printable with no surrounding spaces, "
            f"not {value!r}"
        )


def _check_int(value: object, name: str, where: str, low: int, high: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise MetadataError(
            f"{where}: field {name!r} must be a whole number from {low} to {high}, "
            f"not {value!r}"
        )


def _check_duration(value: object, where: str) -> None:
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not math.isfinite(value)
        or not 0 < value <= MAX_DURATION
    ):
        raise MetadataError(
            f"{where}: field 'duration' must be a number of seconds more than 0 and at "
            f"most {MAX_DURATION:g}, or null for no time limit, not {value!r}"
        )


#: The metadata used when no file is found: development mode, no time limit.
DEV_DEFAULTS: Final = Metadata()

_FIELDS: Final = ("arena", "zone", "mode", "duration", "marker_offset")


def parse_metadata(data: object, source: Path | None = None) -> Metadata:
    """Check the decoded JSON ``data`` of a metadata file and make a :class:`Metadata`.

    In COMP mode every field (``arena``, ``zone``, ``mode``, ``duration``,
    ``marker_offset``) must be present (``duration`` may be ``null``); in DEV mode a
    missing one takes its default. A key j5aio does not know is logged and ignored (the
    competition may keep its own settings in the file).

    :param data: what ``json.load`` gave.
    :param source: the file's path, for the error messages.
    :raises MetadataError: naming the file, the field and what is allowed.
    """
    where = str(source) if source is not None else "metadata"
    if not isinstance(data, dict):
        raise MetadataError(
            f"{where}: must hold a JSON object like "
            '{"arena": "A", "zone": 0, "mode": "DEV"}, '
            f"not a {type(data).__name__}"
        )
    fields: Mapping[str, object] = data
    mode_text = fields.get("mode", Mode.DEV.value)
    if not isinstance(mode_text, str) or mode_text.upper() not in Mode.__members__:
        raise MetadataError(
            f"{where}: field 'mode' must be \"COMP\" or \"DEV\", not {mode_text!r}"
        )
    mode = Mode(mode_text.upper())
    if mode is Mode.COMP:
        missing = [name for name in _FIELDS if name not in fields]
        if missing:
            raise MetadataError(
                f"{where}: in COMP mode every field must be given; missing: "
                + ", ".join(repr(name) for name in missing)
            )
    unknown = sorted(str(key) for key in fields if key not in _FIELDS)
    if unknown:
        LOGGER.info("%s: ignoring fields j5aio does not use: %s", where, ", ".join(unknown))
    arena = fields.get("arena", DEV_DEFAULTS.arena)
    zone = fields.get("zone", DEV_DEFAULTS.zone)
    duration = fields.get("duration", DEV_DEFAULTS.duration)
    offset = fields.get("marker_offset", DEV_DEFAULTS.marker_offset)
    _check_arena(arena, where)
    _check_int(zone, "zone", where, 0, MAX_ZONE)
    if duration is not None:
        _check_duration(duration, where)
    _check_int(offset, "marker_offset", where, 0, MAX_MARKER_OFFSET)
    assert isinstance(arena, str) and isinstance(zone, int) and isinstance(offset, int)
    assert duration is None or isinstance(duration, int | float)
    return Metadata(
        arena=arena,
        zone=zone,
        mode=mode,
        duration=None if duration is None else float(duration),
        marker_offset=offset,
        source=source,
    )


#: astoria's fields read from the metadata stick's ``astoria.json`` (and in its
#: ``astmetad`` status message): the ones j5aio uses, and ``wifi_enabled``.
_ASTORIA_MATCH_FIELDS: Final = frozenset(
    {"arena", "zone", "mode", "marker_offset", "game_timeout", "wifi_enabled"}
)
#: The other fields of astoria's ``astmetad`` message: facts about the robot's software
#: and its WiFi settings, text or null. j5aio checks their type and ignores them (the
#: WiFi password among them is never kept).
_ASTORIA_TEXT_FIELDS: Final = frozenset(
    {
        "astoria_version",
        "kernel_version",
        "arch",
        "python_version",
        "libc_ver",
        "os_name",
        "os_pretty_name",
        "os_version",
        "usercode_entrypoint",
        "wifi_ssid",
        "wifi_psk",
        "wifi_region",
    }
)


def parse_astoria_metadata(data: object, source: str | Path | None = None) -> Metadata:
    """Check metadata in astoria's format and make a :class:`Metadata`.

    astoria (the robot service of Student Robotics' kit) reads ``astoria.json`` at the
    top of the competition's USB stick, for example::

        {"arena": "A", "zone": 1, "mode": "COMP", "marker_offset": 0, "game_timeout": 150}

    and sends the same fields, with facts about the robot's software, as the ``metadata``
    object of its ``astmetad`` status message. The fields and what is allowed:

    - ``arena``: text of 1 to 32 characters (default ``"A"``);
    - ``zone``: a whole number from 0 to :data:`MAX_ZONE` (default 0);
    - ``mode``: ``"COMP"`` or ``"DEV"``, in capitals as astoria spells them (default
      ``"DEV"``);
    - ``marker_offset``: a whole number from 0 to :data:`MAX_MARKER_OFFSET` (default 0);
    - ``game_timeout``: the match's length, a whole number of seconds up to
      :data:`MAX_DURATION`; ``null`` (the default) or ``0`` for no time limit, as the
      kit's own library reads it; it becomes :attr:`Metadata.duration`;
    - ``wifi_enabled``: ``true`` or ``false`` (default ``true``);
    - the message's other fields (``astoria_version``, ``kernel_version``, ``arch``,
      ``python_version``, ``libc_ver``, ``os_name``, ``os_pretty_name``, ``os_version``,
      ``usercode_entrypoint``, ``wifi_ssid``, ``wifi_psk``, ``wifi_region``): text or
      ``null``; they are checked and dropped.

    A field missing takes astoria's default, as astoria itself does. Numbers and
    true/false are taken only as JSON numbers and booleans: ``"2"`` is not a zone and
    ``1`` is not ``true``. A key astoria does not have is an error in COMP mode (a
    misspelt ``game_timeout`` must not give a match without a timer) and is logged in DEV
    mode.

    :param data: the decoded JSON object (``json.loads`` of the file, or the message's
        ``metadata``).
    :param source: where it came from (a file, or a description such as
        ``"astmetad message"``), for the error messages.
    :raises MetadataError: naming the source, the field and what is allowed.
    """
    where = str(source) if source is not None else "astoria metadata"
    if not isinstance(data, dict):
        raise MetadataError(
            f"{where}: must hold a JSON object like "
            '{"arena": "A", "zone": 0, "mode": "COMP", "game_timeout": 150}, '
            f"not a {type(data).__name__}"
        )
    fields: Mapping[str, object] = data
    mode_text = fields.get("mode", Mode.DEV.value)
    if mode_text not in (Mode.COMP.value, Mode.DEV.value):
        raise MetadataError(
            f"{where}: field 'mode' must be \"COMP\" or \"DEV\", not {mode_text!r}"
        )
    mode = Mode(mode_text)
    unknown = sorted(
        str(key)
        for key in fields
        if key not in _ASTORIA_MATCH_FIELDS and key not in _ASTORIA_TEXT_FIELDS
    )
    if unknown and mode is Mode.COMP:
        raise MetadataError(
            f"{where}: in COMP mode every field must be one astoria has; unknown: "
            + ", ".join(repr(name) for name in unknown)
            + "; allowed: "
            + ", ".join(sorted(_ASTORIA_MATCH_FIELDS | _ASTORIA_TEXT_FIELDS))
        )
    if unknown:
        LOGGER.info("%s: ignoring fields astoria does not have: %s", where, ", ".join(unknown))
    for name in sorted(_ASTORIA_TEXT_FIELDS & fields.keys()):
        if fields[name] is not None and not isinstance(fields[name], str):
            raise MetadataError(
                f"{where}: field {name!r} must be text or null, not {fields[name]!r}"
            )
    arena = fields.get("arena", DEV_DEFAULTS.arena)
    zone = fields.get("zone", DEV_DEFAULTS.zone)
    offset = fields.get("marker_offset", DEV_DEFAULTS.marker_offset)
    timeout = fields.get("game_timeout")
    wifi_enabled = fields.get("wifi_enabled", True)
    _check_arena(arena, where)
    _check_int(zone, "zone", where, 0, MAX_ZONE)
    _check_int(offset, "marker_offset", where, 0, MAX_MARKER_OFFSET)
    if timeout is not None:
        try:
            _check_int(timeout, "game_timeout", where, 0, int(MAX_DURATION))
        except MetadataError:
            raise MetadataError(
                f"{where}: field 'game_timeout' must be a whole number of seconds from 0 "
                f"to {MAX_DURATION:g}, or null (or 0) for no time limit, not {timeout!r}"
            ) from None
    if not isinstance(wifi_enabled, bool):
        raise MetadataError(
            f"{where}: field 'wifi_enabled' must be true or false, not {wifi_enabled!r}"
        )
    if mode is Mode.COMP and not timeout:
        LOGGER.warning("%s: a match with no game_timeout: the match timer will not run", where)
    assert isinstance(arena, str) and isinstance(zone, int) and isinstance(offset, int)
    assert timeout is None or isinstance(timeout, int)
    return Metadata(
        arena=arena,
        zone=zone,
        mode=mode,
        duration=float(timeout) if timeout else None,
        marker_offset=offset,
        source=source if isinstance(source, Path) else None,
        wifi_enabled=wifi_enabled,
        origin=source if isinstance(source, str) else None,
    )


def read_metadata_file(path: Path) -> Metadata:
    """Read and check one metadata file.

    :raises MetadataError: it cannot be read, is not JSON, or has a bad field.
    """
    try:
        with path.open("rb") as file:
            raw = file.read(_MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise MetadataError(f"{path}: cannot be read: {exc.strerror or exc}") from None
    if len(raw) > _MAX_FILE_BYTES:
        raise MetadataError(f"{path}: is larger than {_MAX_FILE_BYTES} bytes")
    import json  # (here: most runs have no metadata file to read)

    try:
        data = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise MetadataError(f"{path}: is not UTF-8 text") from None
    except ValueError as exc:  # JSONDecodeError, or a number too long to convert
        raise MetadataError(f"{path}: is not valid JSON: {exc}") from None
    except RecursionError:
        raise MetadataError(f"{path}: is not valid JSON: nested too deeply") from None
    return parse_metadata(data, path)


def media_roots() -> list[Path]:
    """Where removable drives are mounted: ``J5AIO_MEDIA_ROOTS`` or the Linux defaults."""
    override = os.environ.get(MEDIA_ROOTS_VARIABLE)
    if override is not None:
        return [Path(part) for part in override.split(os.pathsep) if part]
    return list(DEFAULT_MEDIA_ROOTS)


def find_usb_sticks(
    roots: Iterable[Path] | None = None,
    *,
    is_mount: Callable[[Path], bool] | None = None,
) -> list[Path]:
    """Every mounted removable drive: mount points one or two levels below a root.

    :param roots: where to look; ``media_roots()`` if omitted.
    :param is_mount: says whether a directory is a mount point; ``os.path.ismount`` if
        omitted.
    :returns: the drives' paths, sorted.
    """
    if is_mount is None:
        is_mount = os.path.ismount
    found: list[Path] = []
    for root in media_roots() if roots is None else roots:
        for child in _subdirectories(root):
            if is_mount(child):
                found.append(child)
                continue
            found.extend(inner for inner in _subdirectories(child) if is_mount(inner))
    return sorted(found)


def _subdirectories(path: Path) -> list[Path]:
    try:
        return sorted(child for child in path.iterdir() if child.is_dir())
    except OSError:
        return []


def find_metadata_file(sticks: Sequence[Path] | None = None) -> Path | None:
    """The metadata file to use: ``J5AIO_METADATA``, else the first stick holding one.

    :param sticks: the drives to look on; :func:`find_usb_sticks` if omitted.
    :raises MetadataError: ``J5AIO_METADATA`` names a file that does not exist.
    """
    named = os.environ.get(METADATA_VARIABLE)
    if named:
        path = Path(named)
        if not path.is_file():
            raise MetadataError(
                f"{path}: no such file (named by the {METADATA_VARIABLE} environment variable)"
            )
        return path
    candidates = [
        stick / METADATA_FILENAME
        for stick in (find_usb_sticks() if sticks is None else sticks)
        if (stick / METADATA_FILENAME).is_file()
    ]
    if len(candidates) > 1:
        LOGGER.warning(
            "More than one USB stick holds %s; using %s", METADATA_FILENAME, candidates[0]
        )
    return candidates[0] if candidates else None


def load_metadata(sticks: Sequence[Path] | None = None) -> Metadata:
    """Find and read the metadata (see the module's documentation for where).

    :param sticks: the drives to look on; :func:`find_usb_sticks` if omitted.
    :returns: the file's metadata, or :data:`DEV_DEFAULTS` if there is no file.
    :raises MetadataError: the file is unreadable, malformed or has a bad field.
    """
    path = find_metadata_file(sticks)
    if path is None:
        return DEV_DEFAULTS
    metadata = read_metadata_file(path)
    LOGGER.debug("Metadata from %s: %s", path, describe(metadata))
    return metadata


def describe(metadata: Metadata) -> str:
    """One line saying what ``metadata`` holds, for logs and headers."""
    duration = "no time limit" if metadata.duration is None else f"{metadata.duration:g} s"
    where = str(metadata.source or metadata.origin or "defaults")
    return (
        f"mode {metadata.mode.value}, arena {metadata.arena}, zone {metadata.zone}, "
        f"{duration}, marker offset {metadata.marker_offset} (from {where})"
    )
