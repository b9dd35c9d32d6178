"""The arena as the robot knows it: where each wall marker is and which way it faces.

A team describes its year's arena once, in code or in a small TOML or JSON file, and
:func:`~j5aio.vision.locate.locate` works out where the robot is from the wall markers it
sees. The frame is the arena's own: the origin at one corner (the simulated arena's
south-west corner), ``x`` along one wall, ``y`` along the other, in mm; a heading or a
facing is measured anticlockwise from the ``x`` axis. In a file, facings are given in
degrees (``facing_degrees``); in code, in radians (``facing``), as every heading in j5aio.

A file lists the markers one by one::

    width = 5750
    length = 5750

    [tokens]                 # or [[tokens]], once for each size of token marker
    ids = [100, 101, 102, 103]
    size = 80

    [[markers]]
    id = 0
    x = 718.75
    y = 0
    z = 250
    size = 150
    facing_degrees = 90

or, for an arena with the same number of markers evenly along each wall (as Student
Robotics' is), says so in a ``[standard]`` table (with the keyword arguments of
:meth:`ArenaMap.standard`)::

    [standard]
    size = 5750
    markers_per_wall = 7
    marker_size = 150

No optional library is needed here.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from j5aio.components._checks import check_number, describe
from j5aio.vision.sizes import FAMILY_SIZE, MarkerSizes

__all__ = ["ArenaMap", "ArenaMapError", "WallMarker"]

_FINITE = 1e12

#: The ids of the standard arena's four tokens, and the size of their markers (mm).
_STANDARD_TOKEN_IDS = range(100, 104)
_STANDARD_TOKEN_MARKER_SIZE = 80.0


class ArenaMapError(ValueError):
    """An arena description (a file or a dictionary) that cannot be used; says what is wrong."""


def _number(value: object, name: str, *, positive: bool = False) -> float:
    if positive:
        return check_number(
            value, name=name, low=1e-9, high=_FINITE, allowed="a number of mm more than 0"
        )
    return check_number(value, name=name, low=-_FINITE, high=_FINITE, allowed="a finite number")


def _marker_id(value: object, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{name} must be an int; got {describe(value)}")
    if not 0 <= value < FAMILY_SIZE:
        raise ValueError(
            f"{name} must be an AprilTag 36h11 id (0 to {FAMILY_SIZE - 1}); got {value}"
        )
    return value


@dataclass(frozen=True)
class WallMarker:
    """A marker fixed on a wall of the arena.

    :param id: its AprilTag 36h11 id.
    :param x: x of its centre, mm.
    :param y: y of its centre, mm.
    :param facing: the heading its face points to (into the arena), radians
        anticlockwise from the x axis.
    :param size: the edge of its black square, mm.
    :param z: height of its centre above the floor, mm.
    :raises TypeError: a value of the wrong type.
    :raises ValueError: an id outside AprilTag 36h11, a size not above 0, a value not finite.
    """

    id: int
    x: float
    y: float
    facing: float
    size: float = 150.0
    z: float = 250.0

    def __post_init__(self) -> None:
        _marker_id(self.id, "a wall marker's id")
        name = f"wall marker {self.id}'s"
        for attribute in ("x", "y", "facing", "z"):
            object.__setattr__(
                self, attribute, _number(getattr(self, attribute), f"{name} {attribute}")
            )
        object.__setattr__(self, "size", _number(self.size, f"{name} size", positive=True))


@dataclass(frozen=True)
class ArenaMap:
    """The wall markers (and the ids of the tokens' markers) of an arena.

    :param markers: the wall markers, each id once.
    :param width: the arena's size along x, mm (0: unknown; then no pose is refused for
        being outside the arena).
    :param length: the arena's size along y, mm (0: unknown).
    :param token_sizes: the token markers' ids and sizes, mm. Tokens move, so their
        markers are never used to locate the robot; they are listed so that the camera's
        table of sizes (:meth:`marker_sizes`) has every marker of the game.
    :raises ValueError: an id is on two wall markers, or on a wall and a token.
    """

    markers: tuple[WallMarker, ...]
    width: float = 0.0
    length: float = 0.0
    token_sizes: Mapping[int, float] = field(default_factory=dict, hash=False)

    def __post_init__(self) -> None:
        markers = tuple(self.markers)
        for marker in markers:
            if not isinstance(marker, WallMarker):
                raise TypeError(f"an arena's markers must be WallMarkers; got {describe(marker)}")
        object.__setattr__(self, "markers", markers)
        seen: set[int] = set()
        for marker in markers:
            if marker.id in seen:
                raise ValueError(f"marker id {marker.id} is on the walls twice")
            seen.add(marker.id)
        tokens = {
            _marker_id(k, "a token's marker id"): _number(
                v, f"the size of token marker {k}", positive=True
            )
            for k, v in dict(self.token_sizes).items()
        }
        both = sorted(seen & set(tokens))
        if both:
            raise ValueError(f"marker ids {both} are both on a wall and on a token")
        object.__setattr__(self, "token_sizes", tokens)
        object.__setattr__(self, "width", _number(self.width, "the arena's width"))
        object.__setattr__(self, "length", _number(self.length, "the arena's length"))
        if self.width < 0 or self.length < 0:
            raise ValueError("an arena's width and length must be 0 (unknown) or more")
        object.__setattr__(self, "_by_id", {m.id: m for m in markers})

    # ------------------------------------------------------------------ questions

    def wall_marker(self, marker_id: int) -> WallMarker | None:
        """The wall marker with this id, or ``None`` if no wall has it."""
        by_id: dict[int, WallMarker] = self.__dict__["_by_id"]
        return by_id.get(marker_id)

    @property
    def token_ids(self) -> frozenset[int]:
        """The ids of the tokens' markers."""
        return frozenset(self.token_sizes)

    def marker_sizes(self) -> MarkerSizes:
        """The table of sizes of every marker in the arena, for the camera.

        ``camera.set_marker_sizes(arena_map.marker_sizes())`` makes the camera's sizes
        agree with the map's (distances are worked out from them).
        """
        return MarkerSizes({**{m.id: m.size for m in self.markers}, **self.token_sizes})

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """Whether the point is inside the arena, or less than ``margin`` mm outside it.

        Always true when the arena's size is unknown (width or length 0).
        """
        if self.width <= 0 or self.length <= 0:
            return True
        return -margin <= x <= self.width + margin and -margin <= y <= self.length + margin

    # ------------------------------------------------------------------ making one

    @classmethod
    def standard(
        cls,
        *,
        size: float = 5750.0,
        markers_per_wall: int = 7,
        marker_size: float = 150.0,
        marker_height: float = 250.0,
    ) -> ArenaMap:
        """The map of a square arena like Student Robotics' (the simulated kit's default).

        ``markers_per_wall`` markers stand evenly along each wall, facing into the arena,
        with ids anticlockwise from 0 at the west end of the south wall; the four tokens
        have ids 100 to 103, with 80 mm markers. The simulated arena
        (:meth:`j5aio.simulator.arena.Arena.standard`) is made from this map.
        """
        markers = []
        spacing = size / (markers_per_wall + 1)
        # (start corner, direction along the wall, facing into the arena) per wall
        walls = (
            ((0.0, 0.0), (1.0, 0.0), math.pi / 2),
            ((size, 0.0), (0.0, 1.0), math.pi),
            ((size, size), (-1.0, 0.0), -math.pi / 2),
            ((0.0, size), (0.0, -1.0), 0.0),
        )
        for w, ((x0, y0), (dx, dy), facing) in enumerate(walls):
            for i in range(markers_per_wall):
                along = spacing * (i + 1)
                markers.append(
                    WallMarker(
                        w * markers_per_wall + i,
                        x0 + dx * along,
                        y0 + dy * along,
                        facing,
                        marker_size,
                        marker_height,
                    )
                )
        return cls(
            tuple(markers),
            width=size,
            length=size,
            token_sizes=dict.fromkeys(_STANDARD_TOKEN_IDS, _STANDARD_TOKEN_MARKER_SIZE),
        )

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ArenaMap:
        """Make a map from a dictionary shaped as the file is (see the module's help).

        :raises ArenaMapError: a key is missing or unknown, or a value is not allowed.
        """
        if not isinstance(data, Mapping):
            raise ArenaMapError(f"an arena description must be a table; got {describe(data)}")
        try:
            return cls._from_dict(data)
        except ArenaMapError:
            raise
        except (TypeError, ValueError, KeyError) as exc:
            raise ArenaMapError(f"the arena description is not usable: {exc}") from exc

    @classmethod
    def _from_dict(cls, data: Mapping[str, Any]) -> ArenaMap:
        _only(data, {"width", "length", "tokens", "markers", "standard"}, "the arena")
        if "standard" in data:
            if "markers" in data:
                raise ArenaMapError("give either [standard] or [[markers]], not both")
            standard = data["standard"]
            if not isinstance(standard, Mapping):
                raise ArenaMapError(f"[standard] must be a table; got {describe(standard)}")
            _only(
                standard,
                {"size", "markers_per_wall", "marker_size", "marker_height"},
                "[standard]",
            )
            base = cls.standard(**standard)
        else:
            entries = data.get("markers")
            if not isinstance(entries, list) or not entries:
                raise ArenaMapError(
                    "the arena must list its wall markers ([[markers]] entries with id, x, "
                    "y, facing_degrees, and optionally size and z) or give a [standard] table"
                )
            base = cls(tuple(_wall_marker(entry) for entry in entries))
        tokens = data.get("tokens")
        token_sizes = dict(base.token_sizes)
        if tokens is not None:
            groups = tokens if isinstance(tokens, list) else [tokens]
            token_sizes = {}
            for group in groups:
                token_sizes.update(_token_group(group))
        return cls(
            base.markers,
            width=data.get("width", base.width),
            length=data.get("length", base.length),
            token_sizes=token_sizes,
        )

    @classmethod
    def load(cls, path: str | Path) -> ArenaMap:
        """Read a map from a ``.toml`` or ``.json`` file (see the module's help for its shape).

        :raises ArenaMapError: the file is not TOML or JSON, or describes no usable arena.
        :raises OSError: the file cannot be read.
        """
        import json  # here: a program that never reads a file never imports them
        import tomllib

        path = Path(path)
        suffix = path.suffix.lower()
        text = path.read_text(encoding="utf-8")
        try:
            if suffix == ".toml":
                data: Any = tomllib.loads(text)
            elif suffix == ".json":
                data = json.loads(text)
            else:
                raise ArenaMapError(
                    f"cannot tell the format of {str(path)!r}: name it .toml or .json"
                )
        except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
            raise ArenaMapError(f"{path} is not valid {suffix[1:].upper()}: {exc}") from exc
        try:
            return cls.from_dict(data)
        except ArenaMapError as exc:
            raise ArenaMapError(f"{path}: {exc}") from exc

    def to_dict(self) -> dict[str, Any]:
        """The map as a dictionary shaped as the file is (``json.dumps`` can write it)."""
        data: dict[str, Any] = {"width": self.width, "length": self.length}
        groups: dict[float, list[int]] = {}
        for marker_id, size in sorted(self.token_sizes.items()):
            groups.setdefault(size, []).append(marker_id)
        if len(groups) == 1:
            (size, ids), = groups.items()
            data["tokens"] = {"ids": ids, "size": size}
        elif groups:
            data["tokens"] = [{"ids": ids, "size": size} for size, ids in groups.items()]
        data["markers"] = [
            {
                "id": m.id,
                "x": m.x,
                "y": m.y,
                "z": m.z,
                "size": m.size,
                "facing_degrees": round(math.degrees(m.facing), 9),
            }
            for m in self.markers
        ]
        return data


def _only(table: Mapping[str, Any], allowed: Iterable[str], where: str) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise ArenaMapError(
            f"{where} has unknown keys {unknown}; allowed: {', '.join(sorted(allowed))}"
        )


def _token_group(group: object) -> dict[int, float]:
    if not isinstance(group, Mapping):
        raise ArenaMapError(
            f"[tokens] must be a table (or a list of tables); got {describe(group)}"
        )
    _only(group, {"ids", "size"}, "[tokens]")
    ids = group.get("ids", [])
    if not isinstance(ids, list):
        raise ArenaMapError(f"[tokens] ids must be a list; got {describe(ids)}")
    size = group.get("size", 80.0)
    return {marker_id: size for marker_id in ids}


def _wall_marker(entry: object) -> WallMarker:
    if not isinstance(entry, Mapping):
        raise ArenaMapError(f"each [[markers]] entry must be a table; got {describe(entry)}")
    _only(entry, {"id", "x", "y", "z", "size", "facing_degrees"}, "a [[markers]] entry")
    missing = [k for k in ("id", "x", "y", "facing_degrees") if k not in entry]
    if missing:
        raise ArenaMapError(f"the [[markers]] entry {dict(entry)} has no {', '.join(missing)}")
    facing = _number(entry["facing_degrees"], f"marker {entry['id']}'s facing_degrees")
    return WallMarker(
        entry["id"],
        entry["x"],
        entry["y"],
        math.radians(facing),
        entry.get("size", 150.0),
        entry.get("z", 250.0),
    )
