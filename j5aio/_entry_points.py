"""The entry points of one group, found without importing :mod:`importlib.metadata`.

:mod:`importlib.metadata` brings the ``email``, ``csv``, ``zipfile`` and ``json`` modules
with it: about 30 modules and a fifth of the time a program on the simulated kit takes to
start. Board plugins (:mod:`j5aio.board_kinds`) only need the entry points of one group,
which installed distributions list in ``<name>-<version>.dist-info/entry_points.txt``
(``.egg-info`` for older installs) in the folders of :data:`sys.path`. :func:`find` reads
those files directly, in the order and with the precedence :mod:`importlib.metadata`
gives them (the first distribution of a name on the path wins). Where it cannot be sure
to see every distribution (a zip file on the path, or an import hook that lists
distributions of its own) it asks :mod:`importlib.metadata` instead.

Reading them means listing every folder of the path and opening each distribution's
file: about a millisecond with the 165 distributions of a development environment, on
every start. So :func:`find` remembers its answer in a small file of the user's cache
folder (``$J5AIO_CACHE_DIR``, else ``$XDG_CACHE_HOME/j5aio``, else ``~/.cache/j5aio``;
``J5AIO_CACHE_DIR=`` with no value turns this off), with what it was read from: the
modification time of every folder of the path, and of each file that named the group.
The answer is used again only while all of those are unchanged, which is so until a
distribution is installed, removed or upgraded in one of the folders (that changes the
folder) or a file that named the group is changed. Folders changed in the last
:data:`_SETTLED` seconds are not remembered: within a clock tick a change might not
show in a folder's time. (A file edited in place in another distribution's folder, to
add the group by hand, is not seen until the path's folders change.)
"""

from __future__ import annotations

import contextlib
import importlib
import os
import re
import stat
import sys
import time

__all__ = ["PluginEntryPoint", "find"]

_SUFFIXES = (".dist-info", ".egg-info")

#: The first line of a remembered answer (changed when its layout changes).
_CACHE_FORMAT = "j5aio entry points 1"
#: Seconds a folder or file must have stayed unchanged for an answer read from it to be
#: remembered (a change within one tick of the file system's clock may not show).
_SETTLED = 2.0


class PluginEntryPoint:
    """One entry point: ``name = value`` in its group, from the distribution ``package``.

    (A plain record rather than a dataclass: every program on the simulated kit reads
    the entry points, and making a dataclass costs as much as the rest of this module.)
    """

    __slots__ = ("name", "package", "value")

    def __init__(self, name: str, value: str, package: str) -> None:
        self.name = name
        self.value = value
        self.package = package

    def __repr__(self) -> str:
        return (
            f"PluginEntryPoint(name={self.name!r}, value={self.value!r}, package={self.package!r})"
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, PluginEntryPoint):
            return NotImplemented
        return (self.name, self.value, self.package) == (other.name, other.value, other.package)

    def __hash__(self) -> int:
        return hash((self.name, self.value, self.package))

    def load(self) -> object:
        """Import the module ``value`` names and return the object it names in it.

        :raises ImportError: the module cannot be imported.
        :raises AttributeError: the module has no such object.
        """
        reference = self.value.split("[", 1)[0].strip()  # extras are not used
        module_name, _, attributes = reference.partition(":")
        obj: object = importlib.import_module(module_name.strip())
        for attribute in filter(None, attributes.strip().split(".")):
            obj = getattr(obj, attribute)
        return obj


def find(group: str) -> list[PluginEntryPoint]:
    """Every entry point of ``group`` of the distributions installed on :data:`sys.path`.

    The answer of an earlier program is used again while the path's folders and the
    files that named the group are unchanged (see above).
    """
    if _other_finders():
        return _from_importlib_metadata(group)
    folders = _folder_states()
    if folders is None:  # a zip file or an egg: only importlib.metadata reads those
        return _from_importlib_metadata(group)
    cache = _cache_file(group)
    if cache is not None:
        remembered = _remembered(cache, group, folders)
        if remembered is not None:
            return remembered
    holders: list[str] = []
    found = _scan(group, holders)
    if found is None:  # (the path changed under us: a folder became a file)
        return _from_importlib_metadata(group)
    if cache is not None:
        _remember(cache, group, folders, holders, found)
    return found


def _from_importlib_metadata(group: str) -> list[PluginEntryPoint]:
    import importlib.metadata

    return [
        PluginEntryPoint(
            entry_point.name,
            entry_point.value,
            entry_point.dist.name if entry_point.dist is not None else "?",
        )
        for entry_point in importlib.metadata.entry_points(group=group)
    ]


def _normalized(name: str) -> str:
    if "." in name or "-" in name or "__" in name:
        return re.sub(r"[-_.]+", "_", name).lower()
    return name.lower()  # (most folders' names are normalized already)


def _other_finders() -> bool:
    """Whether an import hook lists distributions of its own (importlib.metadata asks it)."""
    return any(
        hasattr(finder, "find_distributions") and finder is not _path_finder()
        for finder in sys.meta_path
    )


def _scan(group: str, holders: list[str] | None = None) -> list[PluginEntryPoint] | None:
    """The entry points read from the path's folders, or None if the path holds more.

    :param holders: if given, the paths of the files that name the group (even if they
        give none of its entry points) are added to it.
    """
    seen: set[str] = set()
    found: list[PluginEntryPoint] = []
    for entry in sys.path:
        folder = entry or "."
        if not os.path.isdir(folder):
            if os.path.exists(folder):
                return None  # a zip file or an egg: only importlib.metadata reads those
            continue
        try:
            names = os.listdir(folder)
        except OSError:
            continue
        for name in names:
            if not name.lower().endswith(_SUFFIXES):
                continue
            key = _normalized(name.rpartition(".")[0].split("-", 1)[0])
            if key in seen:
                continue
            seen.add(key)
            found += _read(f"{folder}{os.sep}{name}", group, holders)
    return found


def _path_finder() -> object:
    from importlib.machinery import PathFinder

    return PathFinder


def _read(
    distribution: str, group: str, holders: list[str] | None = None
) -> list[PluginEntryPoint]:
    path = f"{distribution}{os.sep}entry_points.txt"
    # (most distributions have none: asking is cheaper than failing to open it)
    data = _bytes(path) if os.access(path, os.R_OK) else None
    # Most of those that have one list other groups: their files are not decoded.
    if not data or group.encode("utf-8") not in data:
        return []
    if holders is not None:
        holders.append(path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return []
    if f"[{group}]".replace(" ", "") not in text.replace(" ", ""):
        return []
    found: list[tuple[str, str]] = []
    section = None
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line.startswith(("#", ";")):
            continue
        if line.startswith("[") and line.endswith("]"):
            section = line[1:-1].strip()
        elif section == group and "=" in line:
            name, _, value = line.partition("=")
            found.append((name.strip(), value.strip()))
    if not found:
        return []
    package = _package_name(distribution)
    return [PluginEntryPoint(name, value, package) for name, value in found]


def _package_name(distribution: str) -> str:
    """The ``Name`` field of the distribution's metadata (its folder's name as a fallback)."""
    for metadata in ("METADATA", "PKG-INFO"):
        text = _text(os.path.join(distribution, metadata))
        for line in (text or "").splitlines():
            if not line.strip():
                break  # the end of the headers
            key, _, value = line.partition(":")
            if key.strip().lower() == "name" and value.strip():
                return value.strip()
    return os.path.basename(distribution).rpartition(".")[0].split("-", 1)[0]


def _bytes(path: str, *, own: bool = False) -> bytes | None:
    """The file's bytes, or None if it cannot be read.

    (Read through the file descriptor: a file object costs more than the read, and a
    program reads every distribution's entry points at its start.)

    :param own: read it only if it is a file of this user's that no one else may write.
    """
    try:
        descriptor = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        if own and not _owned_by_us_alone(os.fstat(descriptor)):
            return None
        chunks = []
        while chunk := os.read(descriptor, 65536):
            chunks.append(chunk)
    except OSError:
        return None
    finally:
        os.close(descriptor)
    return b"".join(chunks)


def _owned_by_us_alone(status: os.stat_result) -> bool:
    """Whether a file is this user's and no one else may write it (where users exist)."""
    getuid = getattr(os, "getuid", None)
    return getuid is None or (status.st_uid == getuid() and not status.st_mode & 0o022)


def _text(path: str) -> str | None:
    try:
        with open(path, encoding="utf-8") as file:
            return file.read()
    except (OSError, UnicodeDecodeError):
        return None


# --- the answer remembered between programs ---


def _folder_states() -> list[str] | None:
    """One line per folder of the path: its absolute name and modification time.

    None if the path holds a file (a zip, an egg), whose distributions only
    :mod:`importlib.metadata` reads.
    """
    lines = []
    for entry in sys.path:
        try:
            folder = os.path.abspath(entry or ".")
        except OSError:  # (the working folder is gone)
            folder = entry or "."
        try:
            status = os.stat(folder)
        except (OSError, ValueError):
            lines.append(f"{folder}\t-")
            continue
        if not stat.S_ISDIR(status.st_mode):
            return None
        lines.append(f"{folder}\t{status.st_mtime_ns}")
    return lines


def _file_state(path: str) -> str:
    """A file's modification time and size, as remembered (``-`` if it is gone)."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):
        return "-"
    return f"{status.st_mtime_ns}\t{status.st_size}"


def _cache_folder() -> str | None:
    """The folder for the remembered answers, or None when remembering is turned off."""
    chosen = os.environ.get("J5AIO_CACHE_DIR")
    if chosen is not None:
        return os.path.abspath(chosen) if chosen else None
    if os.name == "nt":  # pragma: no cover - Windows
        base = os.environ.get("LOCALAPPDATA", "")
    else:
        base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    if not os.path.isabs(base):
        return None  # (no home to speak of)
    return os.path.join(base, "j5aio")


def _cache_file(group: str) -> str | None:
    """The file remembering ``group``'s entry points for this interpreter and path, if any.

    (One file per interpreter, group and path but its first folder, the program's own: a
    program run from another folder replaces it, so that their number stays small.)
    """
    folder = _cache_folder()
    if folder is None:
        return None
    key = "\0".join([sys.prefix, sys.executable, group, *sys.path[1:]])
    # A short, stable name, needing no module: the key's bytes as a number, modulo the
    # prime 2**61 - 1 (a name shared by chance only means that the answer is read again).
    digest = int.from_bytes(key.encode("utf-8", "replace"), "big") % 0x1FFFFFFFFFFFFFFF
    return os.path.join(folder, f"entry-points-{digest:016x}.txt")


def _header(group: str, folders: list[str]) -> list[str]:
    return [_CACHE_FORMAT, group, str(len(folders)), *folders]


def _remembered(cache: str, group: str, folders: list[str]) -> list[PluginEntryPoint] | None:
    """The answer remembered in ``cache``, if it was read from the path as it is now."""
    data = _own_bytes(cache)
    if data is None:
        return None
    try:
        lines = data.decode("utf-8").split("\n")
        header = _header(group, folders)
        if lines[: len(header)] != header:
            return None
        at = len(header)
        holders = lines[at + 1 : at + 1 + int(lines[at])]
        at += 1 + len(holders)
        entries = lines[at + 1 : at + 1 + int(lines[at])]
        if int(lines[at]) != len(entries) or lines[at + 1 + len(entries) :] != [""]:
            return None  # (cut short, or more than it says)
        for line in holders:
            path, _, state = line.partition("\t")
            if _file_state(path) != state:
                return None
        found = []
        for line in entries:
            name, value, package = line.split("\t")
            found.append(PluginEntryPoint(name, value, package))
    except (ValueError, IndexError):  # (a file of another layout)
        return None
    return found


def _own_bytes(path: str) -> bytes | None:
    """The bytes of a file of this user's that no one else may write, else None.

    (What a remembered answer names is imported: a file another user could have written
    is not read.)
    """
    return _bytes(path, own=True)


def _remember(
    cache: str,
    group: str,
    folders: list[str],
    holders: list[str],
    found: list[PluginEntryPoint],
) -> None:
    """Write the answer to ``cache``, if what it was read from has settled."""
    words = [group, *holders, *(part for e in found for part in (e.name, e.value, e.package))]
    if any("\t" in word or "\n" in word for word in words) or any(
        line.count("\t") != 1 or "\n" in line for line in folders
    ):
        return  # (a name that would not read back)
    settled = time.time_ns() - int(_SETTLED * 1e9)
    files = [f"{path}\t{_file_state(path)}" for path in holders]
    times = [line.split("\t")[1] for line in (*folders, *files)]
    if any(when != "-" and int(when) > settled for when in times):
        return  # (changed a moment ago: another change might not show yet)
    entries = [f"{e.name}\t{e.value}\t{e.package}" for e in found]
    lines = [*_header(group, folders), str(len(files)), *files, str(len(entries)), *entries]
    text = "\n".join(lines) + "\n"
    partial = f"{cache}.{os.getpid()}.{time.monotonic_ns()}.tmp"  # (one per writer)
    try:
        os.makedirs(os.path.dirname(cache), exist_ok=True)
        descriptor = os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        with open(descriptor, "w", encoding="utf-8") as file:
            file.write(text)
        os.replace(partial, cache)  # (whole or not at all, for a program reading it now)
    except (OSError, ValueError):
        with contextlib.suppress(OSError):
            os.unlink(partial)
