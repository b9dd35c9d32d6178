"""Board families with several generations: one group gathers boards from every backend."""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from j5aio.backends.environment import Environment
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.errors import CommunicationError

from .conftest import LampBackend, LampBoard


class LampBoardGen2(LampBoard):
    """A second-generation lamp board: the same components, a new wire protocol."""

    name = "Lamp Board (gen 2)"


class LampGen2Backend(LampBackend):
    """Finds second-generation boards only."""

    board = LampBoardGen2
    serials: Sequence[str] = ("C",)

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        return [LampBoardGen2(serial, cls()) for serial in cls.serials]


class OtherLampBackend(LampBackend):
    """Another backend for the first generation (say, a simulated one)."""


async def test_a_group_gathers_every_generation_in_serial_order() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    env.register_backend(LampGen2Backend)
    group = await env.get_board_group(LampBoard)
    assert [board.serial_number for board in group] == ["A", "B", "C"]
    assert isinstance(group["C"], LampBoardGen2)
    assert all(board.setup_calls == 1 for board in group)
    assert group.backend_classes == (LampBackend, LampGen2Backend)
    assert group.backend_class is LampBackend
    assert "LampBackend, LampGen2Backend" in repr(group)


async def test_asking_for_the_subclass_finds_that_generation_only() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    env.register_backend(LampGen2Backend)
    group = await env.get_board_group(LampBoardGen2)
    assert [board.serial_number for board in group] == ["C"]
    assert env.backends_for(LampBoardGen2) == (LampGen2Backend,)
    assert env.get_backend(LampBoardGen2) is LampGen2Backend


async def test_only_the_new_generation_registered_still_answers_the_family() -> None:
    env = Environment("E")
    env.register_backend(LampGen2Backend)
    group = await env.get_board_group(LampBoard)
    assert [board.serial_number for board in group] == ["C"]
    with pytest.raises(NotImplementedError, match="supports: LampBoardGen2"):
        env.get_backend(LampBoard)


async def test_a_second_backend_for_the_same_class_needs_alongside() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    with pytest.raises(RuntimeError, match=r"already uses LampBackend for LampBoard.*alongside"):
        env.register_backend(OtherLampBackend)
    env.register_backend(OtherLampBackend, alongside=True)
    assert env.backends_for(LampBoard) == (LampBackend, OtherLampBackend)
    assert env.get_backend(LampBoard) is LampBackend
    with pytest.raises(RuntimeError, match="already uses"):
        env.register_backend(OtherLampBackend, alongside=True)


async def test_two_boards_with_one_serial_number_are_an_error() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    env.register_backend(OtherLampBackend, alongside=True)
    with pytest.raises(CommunicationError, match=r"two Lamp.*'A'.*LampBackend and Other"):
        await env.get_board_group(LampBoard)


def test_merge_keeps_every_generation_and_refuses_conflicts() -> None:
    first = Environment("First")
    second = Environment("Second")
    second.register_backend(LampBackend)
    second.register_backend(LampGen2Backend)
    first.merge(second)
    assert first.backends_for(LampBoard) == (LampBackend, LampGen2Backend)
    with pytest.raises(RuntimeError, match="both have a backend for LampBoard, LampBoardGen2"):
        first.merge(second)


def test_group_refuses_a_backend_of_another_family_or_none() -> None:
    with pytest.raises(TypeError, match="drives LampBoard, not LampBoardGen2"):
        BoardGroup(LampBoardGen2, [LampGen2Backend, LampBackend])
    with pytest.raises(TypeError, match="non-empty sequence"):
        BoardGroup(LampBoard, [])


def test_unknown_family_lists_what_is_supported() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    with pytest.raises(NotImplementedError, match="LampBoardGen2; it supports: LampBoard"):
        env.backends_for(LampBoardGen2)
