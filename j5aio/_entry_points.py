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
"""

from __future__ import annotations

import importlib
import os
import re
import sys

__all__ = ["PluginEntryPoint", "find"]

_SUFFIXES = (".dist-info", ".egg-info")


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
            f"PluginEntryPoint(name={self.name!r}, value={self.value!r}, "
            f"package={self.package!r})"
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
    """Every entry point of ``group`` of the distributions installed on :data:`sys.path`."""
    found = _scan(group)
    return found if found is not None else _from_importlib_metadata(group)


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


def _scan(group: str) -> list[PluginEntryPoint] | None:
    """The entry points read from the path's folders, or None if the path holds more."""
    if any(
        hasattr(finder, "find_distributions") and finder is not _path_finder()
        for finder in sys.meta_path
    ):
        return None
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
            found += _read(f"{folder}{os.sep}{name}", group)
    return found


def _path_finder() -> object:
    from importlib.machinery import PathFinder

    return PathFinder


def _read(distribution: str, group: str) -> list[PluginEntryPoint]:
    path = f"{distribution}{os.sep}entry_points.txt"
    # (most distributions have none: asking is cheaper than failing to open it)
    data = _bytes(path) if os.access(path, os.R_OK) else None
    # Most of those that have one list other groups: their files are not decoded.
    if not data or group.encode("utf-8") not in data:
        return []
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


def _bytes(path: str) -> bytes | None:
    """The file's bytes, or None if it cannot be read.

    (Read through the file descriptor: a file object costs more than the read, and a
    program reads every distribution's entry points at its start.)
    """
    try:
        descriptor = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        chunks = []
        while chunk := os.read(descriptor, 65536):
            chunks.append(chunk)
    except OSError:
        return None
    finally:
        os.close(descriptor)
    return b"".join(chunks)


def _text(path: str) -> str | None:
    try:
        with open(path, encoding="utf-8") as file:
            return file.read()
    except (OSError, UnicodeDecodeError):
        return None
