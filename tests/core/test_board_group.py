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
