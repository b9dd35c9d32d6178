from __future__ import annotations

import pytest

from j5aio.backends.environment import Environment

from .conftest import LampBackend, LampBoard


def test_register_and_get() -> None:
    env = Environment("TestEnvironment")
    env.register_backend(LampBackend)
    assert env.supported_boards == {LampBoard}
    assert env.get_backend(LampBoard) is LampBackend
    assert str(env) == "TestEnvironment"
    assert repr(env) == "Environment('TestEnvironment')"


def test_registering_twice_is_refused() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    with pytest.raises(RuntimeError, match="already uses LampBackend for LampBoard"):
        env.register_backend(LampBackend)


def test_unknown_board_lists_the_supported_ones() -> None:
    env = Environment("E")
    with pytest.raises(NotImplementedError, match=r"E does not support LampBoard.*none"):
        env.get_backend(LampBoard)


async def test_get_board_group() -> None:
    env = Environment("E")
    env.register_backend(LampBackend)
    group = await env.get_board_group(LampBoard)
    assert len(group) == 2


def test_merge_and_conflict() -> None:
    first = Environment("First")
    second = Environment("Second")
    second.register_backend(LampBackend)
    first.merge(second)
    assert first.get_backend(LampBoard) is LampBackend
    with pytest.raises(RuntimeError, match="both have a backend for LampBoard"):
        first.merge(second)
