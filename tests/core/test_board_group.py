from __future__ import annotations

from collections.abc import Iterator, Sequence

import pytest

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.errors import CommunicationError

from .conftest import LampBackend, LampBoard


@pytest.fixture
def serials() -> Iterator[None]:
    original = LampBackend.serials
    yield
    LampBackend.serials = original


async def test_boards_are_found_set_up_and_ordered_by_serial() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    assert [b.serial_number for b in group] == ["A", "B"]
    assert len(group) == 2
    assert all(b.setup_calls == 1 for b in group)
    assert set(Board.BOARDS) == set(group.boards)
    assert group.backend_class is LampBackend
    assert group.board_type is LampBoard


async def test_lookup_by_serial_and_position() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    assert group["B"].serial_number == "B"
    assert group[0].serial_number == "A"
    assert group[-1].serial_number == "B"
    assert "A" in group and "Z" not in group


async def test_unknown_serial_lists_the_serials_present() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    with pytest.raises(KeyError, match=r"'Z'.*connected: A, B"):
        group["Z"]


async def test_bad_position_and_bad_key_type() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    with pytest.raises(IndexError, match="there are 2"):
        group[2]
    with pytest.raises(TypeError, match="serial number"):
        group[1.0]  # type: ignore[index]
    with pytest.raises(TypeError, match="serial number"):
        group[True]


async def test_singular_needs_exactly_one(serials: None) -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    with pytest.raises(CommunicationError, match=r"exactly one LampBoard.*found 2"):
        group.singular()
    LampBackend.serials = ()
    await group.update_boards()
    with pytest.raises(CommunicationError, match="found 0 \\(none\\)"):
        group.singular()
    LampBackend.serials = ("only",)
    await group.update_boards()
    assert group.singular().serial_number == "only"


async def test_make_safe_reaches_every_board() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    await group.make_safe()
    assert [b.safe_calls for b in group] == [1, 1]
    assert all(b.lamp_backend.states[0] is False for b in group)


async def test_explicit_ports_are_attached() -> None:
    attached: list[str] = []

    class Attachable(LampBackend):
        serials: Sequence[str] = ()

        @classmethod
        async def attach(cls, port: str) -> Board:
            attached.append(port)
            return LampBoard(f"at-{port}", cls())

    group = await BoardGroup.get_board_group(LampBoard, Attachable, ports=["p1", "p2"])
    assert attached == ["p1", "p2"]
    assert [b.serial_number for b in group] == ["at-p1", "at-p2"]


def test_backend_for_another_board_is_refused() -> None:
    class OtherBoard(LampBoard):
        pass

    with pytest.raises(TypeError, match="choose a backend for OtherBoard"):
        BoardGroup(OtherBoard, LampBackend)


async def test_str_and_repr() -> None:
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    assert str(group) == "Group of Boards - [Lamp Board - A, Lamp Board - B]"
    assert repr(group) == "BoardGroup(board_type=LampBoard, backend_class=LampBackend)"
    assert repr(group[0]) == "<LampBoard serial_number='A'>"


def test_backend_type_is_recorded() -> None:
    assert issubclass(LampBackend, Backend)


class _Loads:
    """Returns ``backends`` and counts its calls."""

    def __init__(self, *backends: type[Backend]) -> None:
        self.backends = backends
        self.calls = 0

    def __call__(self) -> tuple[type[Backend], ...]:
        self.calls += 1
        return self.backends


async def test_a_group_not_looked_in_loads_its_backends_once_when_first_needed() -> None:
    load = _Loads(LampBackend)
    group = BoardGroup._not_looked_in(LampBoard, load)
    assert (len(group), list(group), group.board_type, group.empty_hint) == (0, [], LampBoard, None)
    assert load.calls == 0
    assert repr(group) == "BoardGroup(board_type=LampBoard, backend_class=LampBackend)"
    assert (group.backend_class, group.backend_classes) == (LampBackend, (LampBackend,))
    await group.update_boards()
    assert [board.serial_number for board in group] == ["A", "B"]
    assert load.calls == 1


async def test_a_group_not_looked_in_finds_boards_when_looked_in() -> None:
    load = _Loads(LampBackend)
    group = BoardGroup._not_looked_in(LampBoard, load)
    await group.update_boards()
    assert [board.serial_number for board in group] == ["A", "B"]
    assert load.calls == 1


def test_a_group_not_looked_in_checks_its_backends_when_they_are_loaded() -> None:
    class OtherBoard(LampBoard):
        pass

    group = BoardGroup._not_looked_in(OtherBoard, _Loads(LampBackend))
    with pytest.raises(TypeError, match="choose a backend for OtherBoard"):
        _ = group.backend_class


async def test_joined_groups_keep_unloaded_backends_unloaded() -> None:
    class Gen2Backend(LampBackend):
        serials = ("C",)

    found = await BoardGroup.get_board_group(LampBoard, LampBackend)
    load = _Loads(Gen2Backend)
    joined = BoardGroup.of_groups(LampBoard, [found, BoardGroup._not_looked_in(LampBoard, load)])
    assert [board.serial_number for board in joined] == ["A", "B"]
    assert load.calls == 0
    assert joined.backend_classes == (LampBackend, Gen2Backend)
    assert load.calls == 1
    loaded = BoardGroup.of_groups(LampBoard, [found])
    assert loaded._load_backends is None and loaded.backend_classes == (LampBackend,)
