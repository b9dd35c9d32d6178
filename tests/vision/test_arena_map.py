"""Arena maps: the wall markers in code and in TOML or JSON files (no optional library)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from j5aio.simulator.arena import Arena
from j5aio.vision.arena_map import ArenaMap, ArenaMapError, WallMarker

EXPLICIT = """
width = 4000
length = 3000

[tokens]
ids = [40, 41]
size = 60

[[markers]]
id = 0
x = 1000
y = 0
facing_degrees = 90

[[markers]]
id = 1
x = 4000
y = 1500
z = 300
size = 200
facing_degrees = 180
"""


def test_the_standard_map_is_the_simulated_arenas_and_its_sizes_agree_with_the_camera() -> None:
    arena = Arena.standard()
    arena_map = ArenaMap.standard()
    assert arena_map == arena.arena_map()
    assert [m.id for m in arena_map.markers] == list(range(28))
    assert arena_map.token_ids == {100, 101, 102, 103}
    assert dict(arena_map.marker_sizes()) == dict(arena.marker_sizes())
    first = arena_map.wall_marker(0)
    assert first is not None
    assert (first.x, first.y, first.z, first.size) == (718.75, 0.0, 250.0, 150.0)
    assert first.facing == pytest.approx(math.pi / 2)
    assert arena_map.wall_marker(100) is None
    assert hash(arena_map) == hash(ArenaMap.standard())


def test_a_toml_file_lists_the_markers(tmp_path: Path) -> None:
    path = tmp_path / "arena.toml"
    path.write_text(EXPLICIT)
    arena_map = ArenaMap.load(path)
    assert (arena_map.width, arena_map.length) == (4000.0, 3000.0)
    assert arena_map.token_sizes == {40: 60.0, 41: 60.0}
    zero, one = arena_map.markers
    assert zero == WallMarker(0, 1000.0, 0.0, math.radians(90), 150.0, 250.0)
    assert (one.size, one.z) == (200.0, 300.0)
    assert one.facing == pytest.approx(math.pi)
    assert arena_map.marker_sizes() == {0: 150.0, 1: 200.0, 40: 60.0, 41: 60.0}


def test_a_map_survives_a_json_round_trip(tmp_path: Path) -> None:
    arena_map = ArenaMap.standard(size=4000, markers_per_wall=5)
    path = tmp_path / "arena.json"
    path.write_text(json.dumps(arena_map.to_dict()))
    again = ArenaMap.load(path)
    assert [m.id for m in again.markers] == [m.id for m in arena_map.markers]
    for a, b in zip(again.markers, arena_map.markers, strict=True):
        assert (a.x, a.y, a.z, a.size) == (b.x, b.y, b.z, b.size)
        assert math.remainder(a.facing - b.facing, math.tau) == pytest.approx(0.0, abs=1e-9)
    assert again.token_sizes == arena_map.token_sizes


def test_tokens_of_several_sizes_are_listed_in_groups() -> None:
    arena_map = ArenaMap(
        (WallMarker(0, 0.0, 10.0, 0.0),), token_sizes={5: 80.0, 6: 80.0, 7: 100.0}
    )
    data = arena_map.to_dict()
    assert data["tokens"] == [{"ids": [5, 6], "size": 80.0}, {"ids": [7], "size": 100.0}]
    assert ArenaMap.from_dict(data).token_sizes == arena_map.token_sizes
    assert "tokens" not in ArenaMap((WallMarker(0, 0.0, 10.0, 0.0),)).to_dict()


def test_a_standard_table_makes_a_standard_arena() -> None:
    arena_map = ArenaMap.from_dict(
        {"standard": {"size": 3000, "markers_per_wall": 3}, "tokens": {"ids": [90]}}
    )
    assert len(arena_map.markers) == 12
    assert arena_map.width == 3000.0
    assert arena_map.token_sizes == {90: 80.0}


def test_contains_allows_a_margin_and_an_unknown_size() -> None:
    arena_map = ArenaMap.standard()
    assert arena_map.contains(10.0, 5740.0)
    assert not arena_map.contains(-100.0, 100.0)
    assert arena_map.contains(-100.0, 100.0, margin=150.0)
    assert ArenaMap((WallMarker(0, 0.0, 0.0, 0.0),)).contains(-1e6, 1e6)


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({"markers": []}, "must list its wall markers"),
        ({"walls": 4}, "unknown keys ['walls']"),
        ({"standard": {"size": 3000}, "markers": [{}]}, "either [standard] or [[markers]]"),
        ({"standard": 5}, "[standard] must be a table"),
        ({"standard": {"colour": "red"}}, "[standard] has unknown keys"),
        ({"markers": [5]}, "must be a table"),
        ({"markers": [{"id": 1, "x": 0, "y": 0}]}, "has no facing_degrees"),
        ({"markers": [{"id": 1, "x": 0, "y": 0, "facing_degrees": 0, "w": 1}]}, "unknown keys"),
        ({"markers": [{"id": 1, "x": "a", "y": 0, "facing_degrees": 0}]}, "x must be"),
        ({"markers": [{"id": 900, "x": 0, "y": 0, "facing_degrees": 0}]}, "0 to 586"),
        (
            {"markers": [{"id": 1, "x": 0, "y": 0, "facing_degrees": 0}] * 2},
            "on the walls twice",
        ),
        (
            {"markers": [{"id": 1, "x": 0, "y": 0, "facing_degrees": 0}], "tokens": {"ids": [1]}},
            "both on a wall and on a token",
        ),
        ({"standard": {}, "tokens": 3}, "[tokens] must be a table"),
        ({"standard": {}, "tokens": {"ids": 3}}, "ids must be a list"),
        ({"standard": {}, "tokens": {"id": [3]}}, "[tokens] has unknown keys"),
        ({"standard": {}, "width": -5}, "0 (unknown) or more"),
    ],
)
def test_a_bad_description_says_what_is_wrong(data: dict[str, object], message: str) -> None:
    with pytest.raises(ArenaMapError) as caught:
        ArenaMap.from_dict(data)
    assert message in str(caught.value)


def test_a_description_must_be_a_table() -> None:
    with pytest.raises(ArenaMapError, match="must be a table"):
        ArenaMap.from_dict([1, 2])  # type: ignore[arg-type]


def test_files_of_other_formats_or_bad_syntax_are_refused(tmp_path: Path) -> None:
    (tmp_path / "arena.yaml").write_text("width: 5")
    with pytest.raises(ArenaMapError, match=r"name it \.toml or \.json"):
        ArenaMap.load(tmp_path / "arena.yaml")
    (tmp_path / "arena.toml").write_text("width = = 5")
    with pytest.raises(ArenaMapError, match="not valid TOML"):
        ArenaMap.load(tmp_path / "arena.toml")
    (tmp_path / "arena.json").write_text('{"markers": []}')
    with pytest.raises(ArenaMapError, match=r"arena\.json: .*wall markers"):
        ArenaMap.load(tmp_path / "arena.json")


def test_wall_markers_and_maps_check_their_values() -> None:
    with pytest.raises(TypeError, match="id must be an int"):
        WallMarker(1.5, 0.0, 0.0, 0.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="size must be a number of mm more than 0"):
        WallMarker(1, 0.0, 0.0, 0.0, size=0.0)
    with pytest.raises(ValueError, match="facing must be a finite number"):
        WallMarker(1, 0.0, 0.0, math.nan)
    with pytest.raises(TypeError, match="must be WallMarkers"):
        ArenaMap(((1, 0.0, 0.0, 0.0),))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="size of token marker 5"):
        ArenaMap((), token_sizes={5: -1.0})
