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
import stat
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from enum import StrEnum
from pathlib import Path
from typing import Final

__all__ = [
    "ASTORIA_FILENAME",
    "DEFAULT_MEDIA_ROOTS",
    "DEV_DEFAULTS",
    "MAX_DURATION",
    "MAX_MARKER_OFFSET",
    "MAX_ZONE",
    "MEDIA_ROOTS_VARIABLE",
    "METADATA_FILENAME",
    "METADATA_VARIABLE",
    "MIN_DURATION",
    "SBOT_MATCH_DURATION",
    "SBOT_METADATA_VARIABLE",
    "Metadata",
    "MetadataError",
    "MetadataFormat",
    "Mode",
    "describe",
    "detect_format",
    "find_metadata_file",
    "find_metadata_files",
    "find_usb_sticks",
    "load_metadata",
    "parse_astoria_metadata",
    "parse_metadata",
    "parse_sbot_metadata",
    "read_metadata_file",
]

LOGGER = logging.getLogger(__name__)

#: The file's name at the top of a USB stick.
METADATA_FILENAME: Final = "metadata.json"
#: astoria's metadata file at the top of the competition's USB stick.
ASTORIA_FILENAME: Final = "astoria.json"
#: sbot's environment variable naming the folder that holds its metadata file.
SBOT_METADATA_VARIABLE: Final = "SBOT_METADATA_PATH"
#: The length of a match in sbot's format, in seconds (sbot's own figure).
SBOT_MATCH_DURATION: Final = 150.0
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
#: The shortest match allowed, in seconds: a tenth of a second (shorter ones are slips,
#: such as ``1e-3`` for ``1e3``, and would end the match as it starts).
MIN_DURATION: Final = 0.1
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
    :param duration: the match's length in seconds (:data:`MIN_DURATION` to
        :data:`MAX_DURATION`), or ``None`` for no time limit.
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
        or not MIN_DURATION <= value <= MAX_DURATION
    ):
        raise MetadataError(
            f"{where}: field 'duration' must be a number of seconds from {MIN_DURATION:g} "
            f"to {MAX_DURATION:g}, or null for no time limit, not {value!r}"
        )


#: The metadata used when no file is found: development mode, no time limit.
DEV_DEFAULTS: Final = Metadata()

_FIELDS: Final = ("arena", "zone", "mode", "duration", "marker_offset")


def _json_object(data: object, where: str, example: str) -> Mapping[str, object]:
    """``data`` as the JSON object a metadata file must hold (``example`` shows one)."""
    if not isinstance(data, dict):
        raise MetadataError(
            f"{where}: must hold a JSON object like {example}, not a {type(data).__name__}"
        )
    return data


def _mode(fields: Mapping[str, object], where: str, *, any_case: bool) -> Mode:
    """The ``mode`` field: ``"COMP"`` or ``"DEV"`` (in any case, if ``any_case``); DEV if absent."""
    given = fields.get("mode", Mode.DEV.value)
    text = given.upper() if any_case and isinstance(given, str) else given
    if text not in (Mode.COMP.value, Mode.DEV.value):
        raise MetadataError(f"{where}: field 'mode' must be \"COMP\" or \"DEV\", not {given!r}")
    return Mode(text)


def parse_metadata(data: object, source: Path | None = None) -> Metadata:
    """Check the decoded JSON ``data`` of a metadata file and make a :class:`Metadata`.

    This is j5aio's own format. In COMP mode every field (``arena``, ``zone``, ``mode``,
    ``duration``, ``marker_offset``) must be present (``duration`` may be ``null``) and
    no other key is allowed (a misspelt field must not change the match); in DEV mode a
    missing field takes its default and another key is logged and ignored.

    :param data: what ``json.load`` gave.
    :param source: the file's path, for the error messages.
    :raises MetadataError: naming the file, the field and what is allowed.
    """
    where = str(source) if source is not None else "metadata"
    fields = _json_object(data, where, '{"arena": "A", "zone": 0, "mode": "DEV"}')
    mode = _mode(fields, where, any_case=True)
    if mode is Mode.COMP:
        missing = [name for name in _FIELDS if name not in fields]
        if missing:
            raise MetadataError(
                f"{where}: in COMP mode every field must be given; missing: "
                + ", ".join(repr(name) for name in missing)
            )
    unknown = sorted(str(key) for key in fields if key not in _FIELDS)
    if unknown and mode is Mode.COMP:
        raise MetadataError(
            f"{where}: in COMP mode every field must be one of j5aio's; unknown: "
            + ", ".join(repr(name) for name in unknown)
            + "; allowed: "
            + ", ".join(_FIELDS)
        )
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
      kit's own library reads it; it becomes the :class:`Metadata`'s ``duration``;
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
    fields = _json_object(
        data, where, '{"arena": "A", "zone": 0, "mode": "COMP", "game_timeout": 150}'
    )
    mode = _mode(fields, where, any_case=False)
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


#: sbot's fields: both must be given.
_SBOT_FIELDS: Final = ("zone", "is_competition")


def parse_sbot_metadata(data: object, source: str | Path | None = None) -> Metadata:
    """Check metadata in sbot's format (SourceBots' kit) and make a :class:`Metadata`.

    sbot reads ``metadata.json`` below ``SBOT_METADATA_PATH``, for example
    ``{"zone": 2, "is_competition": true}``. Both fields must be given: ``zone`` a
    whole number from 0 to :data:`MAX_ZONE`, ``is_competition`` ``true`` or ``false``.
    A match (``true``) lasts :data:`SBOT_MATCH_DURATION` seconds, as in sbot; the
    arena is ``"A"`` and the marker offset 0. Another key is an error in a match and is
    logged otherwise.

    :param data: the decoded JSON object.
    :param source: the file's path (or a description), for the error messages.
    :raises MetadataError: naming the source, the field and what is allowed.
    """
    where = str(source) if source is not None else "sbot metadata"
    fields = _json_object(data, where, '{"zone": 0, "is_competition": true}')
    missing = [name for name in _SBOT_FIELDS if name not in fields]
    if missing:
        raise MetadataError(
            f"{where}: sbot's format needs both 'zone' and 'is_competition'; missing: "
            + ", ".join(repr(name) for name in missing)
        )
    competition = fields["is_competition"]
    if not isinstance(competition, bool):
        raise MetadataError(
            f"{where}: field 'is_competition' must be true or false, not {competition!r}"
        )
    zone = fields["zone"]
    _check_int(zone, "zone", where, 0, MAX_ZONE)
    assert isinstance(zone, int)
    unknown = sorted(str(key) for key in fields if key not in _SBOT_FIELDS)
    if unknown and competition:
        raise MetadataError(
            f"{where}: in a match every field must be one of sbot's; unknown: "
            + ", ".join(repr(name) for name in unknown)
            + "; allowed: 'zone', 'is_competition'"
        )
    if unknown:
        LOGGER.info("%s: ignoring fields sbot does not have: %s", where, ", ".join(unknown))
    return Metadata(
        zone=zone,
        mode=Mode.COMP if competition else Mode.DEV,
        duration=SBOT_MATCH_DURATION if competition else None,
        source=source if isinstance(source, Path) else None,
        origin=source if isinstance(source, str) else None,
    )


class MetadataFormat(StrEnum):
    """The formats of metadata file j5aio reads."""

    #: j5aio's own: ``{"arena", "zone", "mode", "duration", "marker_offset"}``
    #: (:func:`parse_metadata`).
    J5AIO = "j5aio"
    #: astoria's ``astoria.json`` (:func:`parse_astoria_metadata`).
    ASTORIA = "astoria"
    #: sbot's ``metadata.json`` (:func:`parse_sbot_metadata`).
    SBOT = "sbot"


#: The keys that only one format has: a file holding one of them is in that format.
_FORMAT_MARKS: Final = {
    MetadataFormat.J5AIO: frozenset({"duration"}),
    MetadataFormat.ASTORIA: frozenset({"game_timeout", "wifi_enabled"}) | _ASTORIA_TEXT_FIELDS,
    MetadataFormat.SBOT: frozenset({"is_competition"}),
}
_PARSERS: Final[dict[MetadataFormat, Callable[[object, Path], Metadata]]] = {
    MetadataFormat.J5AIO: parse_metadata,
    MetadataFormat.ASTORIA: parse_astoria_metadata,
    MetadataFormat.SBOT: parse_sbot_metadata,
}


def detect_format(data: object, path: Path) -> MetadataFormat:
    """Which format the decoded file ``data`` at ``path`` is in.

    A file named :data:`ASTORIA_FILENAME` is astoria's. Otherwise the keys say: only
    j5aio's has ``duration``, only astoria's ``game_timeout``, ``wifi_enabled`` (and
    the fields of astoria's message), only sbot's ``is_competition``. A file with none
    of them is j5aio's, except in COMP mode, where it would not say how long the match
    is.

    :raises MetadataError: the file mixes two formats, or is in COMP mode without saying
        which format (and so how long the match is).
    """
    if path.name == ASTORIA_FILENAME or not isinstance(data, dict):
        return MetadataFormat.ASTORIA if path.name == ASTORIA_FILENAME else MetadataFormat.J5AIO
    keys = {str(key) for key in data}
    found = {
        kind: sorted(keys & marks) for kind, marks in _FORMAT_MARKS.items() if keys & marks
    }
    if len(found) > 1:
        raise MetadataError(
            f"{path}: mixes the fields of "
            + " and ".join(
                f"{kind.value}'s format ({', '.join(map(repr, names))})"
                for kind, names in found.items()
            )
            + "; a metadata file must be in one format"
        )
    if found:
        return next(iter(found))
    mode = data.get("mode")
    if isinstance(mode, str) and mode.upper() == Mode.COMP.value:
        raise MetadataError(
            f"{path}: in COMP mode the file must say how long the match is, so that its "
            "format is clear: 'duration' (j5aio's format, null for no time limit) or "
            "'game_timeout' (astoria's); sbot's format is "
            '{"zone": 0, "is_competition": true}'
        )
    return MetadataFormat.J5AIO


def _refuse_duplicate_keys(pairs: list[tuple[str, object]]) -> dict[str, object]:
    result: dict[str, object] = {}
    for key, value in pairs:
        if key in result:
            raise _DuplicateKeyError(key)
        result[key] = value
    return result


class _DuplicateKeyError(ValueError):
    """A JSON object has a key twice (raised while decoding, named in the error)."""


def read_metadata_file(path: Path, kind: MetadataFormat | None = None) -> Metadata:
    """Read and check one metadata file.

    The file must be a regular file (a link to one is followed) of at most 64 KiB of
    UTF-8 JSON (a byte-order mark is allowed) with no key given twice.

    :param path: the file.
    :param kind: its format; if omitted, :func:`detect_format` says.
    :raises MetadataError: it cannot be read, is not a regular file, is too large, is not
        JSON, is ambiguous, or has a bad field.
    """
    raw = _read_regular_file(path)
    import json  # (here: most runs have no metadata file to read)

    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise MetadataError(f"{path}: is not UTF-8 text") from None
    try:
        data = json.loads(text, object_pairs_hook=_refuse_duplicate_keys)
    except _DuplicateKeyError as exc:
        raise MetadataError(
            f"{path}: field {exc.args[0]!r} is given more than once; give each field once"
        ) from None
    except ValueError as exc:  # JSONDecodeError, or a number too long to convert
        raise MetadataError(f"{path}: is not valid JSON: {exc}") from None
    except RecursionError:
        raise MetadataError(f"{path}: is not valid JSON: nested too deeply") from None
    if kind is None:
        kind = detect_format(data, path)
    metadata = _PARSERS[kind](data, path)
    LOGGER.debug("%s: read in %s's format", path, kind.value)
    return metadata


def _read_regular_file(path: Path) -> bytes:
    """The first bytes of ``path``, refusing what is not a regular file (a FIFO would hang)."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        descriptor = os.open(path, flags)
    except OSError as exc:
        raise MetadataError(f"{path}: cannot be read: {exc.strerror or exc}") from None
    mode = os.fstat(descriptor).st_mode
    if not stat.S_ISREG(mode):
        os.close(descriptor)
        raise MetadataError(
            f"{path}: must be a regular file holding JSON, not {_kind_of_file(mode)}"
        )
    with os.fdopen(descriptor, "rb") as file:
        try:
            raw = file.read(_MAX_FILE_BYTES + 1)
        except OSError as exc:
            raise MetadataError(f"{path}: cannot be read: {exc.strerror or exc}") from None
    if len(raw) > _MAX_FILE_BYTES:
        raise MetadataError(f"{path}: is larger than {_MAX_FILE_BYTES} bytes")
    return raw


def _kind_of_file(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a special file"  # pragma: no cover - a socket cannot be opened, so never seen


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


def _files_in(folder: Path) -> list[Path]:
    """The metadata files at the top of ``folder``, whatever they are.

    Even a directory or a FIFO by one of those names counts: reading it then says what
    is wrong, rather than the robot running in development mode.
    """
    return [
        folder / name
        for name in (METADATA_FILENAME, ASTORIA_FILENAME)
        if os.path.lexists(folder / name)
    ]


def _named_file() -> Path | None:
    named = os.environ.get(METADATA_VARIABLE)
    if not named:
        return None
    path = Path(named)
    if not os.path.lexists(path):
        raise MetadataError(
            f"{path}: no such file (named by the {METADATA_VARIABLE} environment variable)"
        )
    return path


def _sbot_files() -> list[tuple[Path, MetadataFormat | None]]:
    """The files below ``SBOT_METADATA_PATH``: at its top, else one level down (as sbot).

    A ``metadata.json`` there is in sbot's format (sbot's own folder), an
    ``astoria.json`` in astoria's (as sr-robot3's simulator puts it there).
    """
    named = os.environ.get(SBOT_METADATA_VARIABLE)
    if not named:
        return []
    folder = Path(named)
    if not folder.is_dir():
        raise MetadataError(
            f"{folder}: no such directory (named by the {SBOT_METADATA_VARIABLE} "
            "environment variable, which names the folder holding metadata.json or "
            "astoria.json)"
        )
    found = _files_in(folder)
    for child in _subdirectories(folder):
        found += _files_in(child)
    return [
        (path, MetadataFormat.SBOT if path.name == METADATA_FILENAME else None)
        for path in found
    ]


def _candidates(sticks: Sequence[Path] | None) -> list[tuple[Path, MetadataFormat | None]]:
    """The metadata files to read, most wanted first, each with its format if it is known."""
    named = _named_file()
    if named is not None:
        return [(named, None)]
    from_sbot = _sbot_files()
    if from_sbot:
        return from_sbot
    return [
        (path, None)
        for stick in (find_usb_sticks() if sticks is None else sticks)
        for path in _files_in(stick)
    ]


def find_metadata_files(sticks: Sequence[Path] | None = None) -> list[Path]:
    """The metadata files that would be read, most wanted first (see :func:`load_metadata`).

    :param sticks: the drives to look on; :func:`find_usb_sticks` if omitted.
    :raises MetadataError: ``J5AIO_METADATA`` names nothing, or ``SBOT_METADATA_PATH``
        is not a directory.
    """
    return [path for path, _ in _candidates(sticks)]


def find_metadata_file(sticks: Sequence[Path] | None = None) -> Path | None:
    """The first of :func:`find_metadata_files`, or ``None``.

    :param sticks: the drives to look on; :func:`find_usb_sticks` if omitted.
    :raises MetadataError: as :func:`find_metadata_files`.
    """
    found = find_metadata_files(sticks)
    return found[0] if found else None


def load_metadata(sticks: Sequence[Path] | None = None) -> Metadata:
    """The match's metadata, from the first of these that has some.

    1. the robot service (astoria over MQTT, :mod:`j5aio.competition.service_state`):
       what it last said;
    2. the file named by ``J5AIO_METADATA`` (it must exist then);
    3. ``metadata.json`` (in sbot's format) or ``astoria.json`` in the folder named by
       ``SBOT_METADATA_PATH``, or in its subfolders (it must be a folder then);
    4. ``metadata.json`` or ``astoria.json`` at the top of each USB stick.

    Elsewhere each file may be in j5aio's, astoria's or sbot's format
    (:func:`detect_format`).
    Where several files are found they must agree (each stick's copy of the same
    metadata, say); a file that cannot be read is an error, never skipped.

    :param sticks: the drives to look on; :func:`find_usb_sticks` if omitted.
    :returns: the metadata found, or :data:`DEV_DEFAULTS` if there is none.
    :raises MetadataError: a file is unreadable, malformed, ambiguous or has a bad
        field, or two files disagree.
    """
    from j5aio.competition import service_state

    live = service_state.metadata()
    if live is not None:
        return live
    candidates = _candidates(sticks)
    if not candidates:
        return DEV_DEFAULTS
    chosen = read_metadata_file(*candidates[0])
    for other, kind in candidates[1:]:
        if _match_of(read_metadata_file(other, kind)) != _match_of(chosen):
            raise MetadataError(
                f"{other}: disagrees with {candidates[0][0]} ({describe(chosen)}); remove "
                "the file that is wrong"
            )
    paths = [path for path, _ in candidates]
    if len(paths) > 1:
        LOGGER.info("Metadata files agree: %s", ", ".join(map(str, paths)))
    LOGGER.debug("Metadata from %s: %s", paths[0], describe(chosen))
    return chosen


def _match_of(metadata: Metadata) -> Metadata:
    """What must agree between two files of the same match (not the file, nor extras)."""
    return replace(metadata, source=None, origin=None, wifi_enabled=None)


def describe(metadata: Metadata) -> str:
    """One line saying what ``metadata`` holds, for logs and headers."""
    duration = "no time limit" if metadata.duration is None else f"{metadata.duration:g} s"
    where = str(metadata.source or metadata.origin or "defaults")
    return (
        f"mode {metadata.mode.value}, arena {metadata.arena}, zone {metadata.zone}, "
        f"{duration}, marker offset {metadata.marker_offset} (from {where})"
    )
