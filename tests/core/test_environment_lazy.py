"""Backends registered lazily: loaded on first use, skipped while idle, checked when loaded."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence

import pytest

from j5aio.backends.backend import Backend
from j5aio.backends.environment import Environment
from j5aio.boards.board import Board

from .conftest import LampBackend, LampBoard


class LampBoardGen2(LampBoard):
    """A later generation of the lamp board."""


class LampGen2Backend(LampBackend):
    board = LampBoardGen2
    serials = ("C",)

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        return [LampBoardGen2(serial, cls()) for serial in cls.serials]


class Loader:
    """Returns ``backend`` and counts its calls."""

    def __init__(self, backend: object) -> None:
        self.backend = backend
        self.calls = 0

    def __call__(self) -> type[Backend]:
        self.calls += 1
        return self.backend  # type: ignore[return-value]


def test_nothing_is_loaded_to_know_the_supported_boards() -> None:
    env = Environment("E")
    load = Loader(LampBackend)
    env.register_lazily(LampBoard, load)
    assert env.supported_boards == {LampBoard}
    assert load.calls == 0
    assert env.get_backend(LampBoard) is LampBackend
    assert env.get_backend(LampBoard) is LampBackend
    assert load.calls == 1


async def test_a_board_group_loads_the_backends_of_that_board_only() -> None:
    env = Environment("E")
    lamps, others = Loader(LampBackend), Loader(LampGen2Backend)
    env.register_lazily(LampBoard, lamps)
    env.register_lazily(LampBoardGen2, others)
    group = await env.get_board_group(LampBoardGen2)
    assert [board.serial_number for board in group] == ["C"]
    assert (lamps.calls, others.calls) == (0, 1)
    # The family's class gathers both generations, in registration order.
    assert env.backends_for(LampBoard) == (LampBackend, LampGen2Backend)
    assert [board.serial_number for board in await env.get_board_group(LampBoard)] == [
        "A", "B", "C",
    ]
    assert (lamps.calls, others.calls) == (1, 1)


def test_reading_backends_or_the_mapping_loads_all_in_order() -> None:
    env = Environment("E")
    env.register_lazily(LampBoardGen2, Loader(LampGen2Backend))
    env.register_backend(LampBackend)
    assert env.backends == [LampGen2Backend, LampBackend]
    assert env.board_backend_mapping == {
        LampBoardGen2: LampGen2Backend, LampBoard: LampBackend,
    }


async def test_an_idle_backend_is_neither_loaded_nor_asked() -> None:
    env = Environment("E")
    idle = {"gen1": True}
    lamps, others = Loader(LampBackend), Loader(LampGen2Backend)
    env.register_lazily(LampBoard, lamps, idle=lambda: idle["gen1"])
    env.register_lazily(LampBoardGen2, others)
    group = await env.get_board_group(LampBoard)
    assert [board.serial_number for board in group] == ["C"]
    assert lamps.calls == 0
    idle["gen1"] = False
    group = await env.get_board_group(LampBoard)
    assert [board.serial_number for board in group] == ["A", "B", "C"]
    assert lamps.calls == 1


async def test_when_every_backend_is_idle_the_group_is_empty_and_nobody_is_asked() -> None:
    asked: list[str] = []

    class Recording(LampBackend):
        @classmethod
        async def discover(cls) -> Sequence[Board]:
            asked.append("discover")
            return await super().discover()

    env = Environment("E")
    load = Loader(Recording)
    env.register_lazily(LampBoard, load, idle=lambda: True)
    group = await env.get_board_group(LampBoard)
    assert len(group) == 0
    assert load.calls == 0  # not even loaded, until the group needs it
    assert group.backend_class is Recording
    assert group.backend_classes == (Recording,)
    assert load.calls == 1
    assert asked == []


async def test_an_empty_group_loads_its_idle_backend_to_look_again() -> None:
    idle = [True]
    env = Environment("E")
    load = Loader(LampBackend)
    env.register_lazily(LampBoard, load, idle=lambda: idle[0])
    env.register_lazily(LampBoardGen2, Loader(LampGen2Backend), idle=lambda: True)
    group = await env.get_board_group(LampBoard)
    assert (len(group), load.calls) == (0, 0)
    idle[0] = False
    await group.update_boards()  # (looking again asks the first backend, as it always did)
    assert [board.serial_number for board in group] == ["A", "B"]
    assert load.calls == 1


async def test_an_empty_group_s_backend_is_checked_when_it_is_loaded() -> None:
    env = Environment("E")
    env.register_lazily(LampBoardGen2, Loader(LampBackend), idle=lambda: True)
    group = await env.get_board_group(LampBoardGen2)
    with pytest.raises(TypeError, match=r"LampBackend .*drives LampBoard"):
        _ = group.backend_classes


def test_might_find_says_whether_a_board_group_would_ask_a_backend() -> None:
    env = Environment("E")
    idle = {"gen2": True}
    lamps = Loader(LampGen2Backend)
    env.register_lazily(LampBoardGen2, lamps, idle=lambda: idle["gen2"])
    assert not env.might_find(LampBoardGen2)
    assert not env.might_find(LampBoard)  # its only backend, for the subclass, is idle
    idle["gen2"] = False
    assert env.might_find(LampBoardGen2) and env.might_find(LampBoard)
    assert lamps.calls == 0  # nothing loaded to tell
    env.register_backend(LampBackend)
    idle["gen2"] = True
    assert env.might_find(LampBoard) and not env.might_find(LampBoardGen2)
    assert not Environment("Empty").might_find(LampBoard)


async def test_an_unsupported_board_is_refused_lazily_too() -> None:
    env = Environment("E")
    env.register_lazily(LampBoardGen2, Loader(LampGen2Backend), idle=lambda: True)

    class Other(LampBoard):
        pass

    with pytest.raises(NotImplementedError, match=r"E does not support Other.*LampBoardGen2"):
        await env.get_board_group(Other)
    with pytest.raises(NotImplementedError, match="does not support Other"):
        env.get_backend(Other)


@pytest.mark.parametrize(
    ("loaded", "message"),
    [
        (object, "the backend loaded for LampBoard is not a Backend"),
        ("LampBackend", "the backend loaded for LampBoard is not a Backend"),
    ],
)
def test_what_a_loader_returns_is_checked(loaded: object, message: str) -> None:
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(loaded))
    with pytest.raises(TypeError, match=message):
        env.get_backend(LampBoard)


def test_a_loaded_backend_must_drive_the_board_it_was_registered_for() -> None:
    env = Environment("E")
    env.register_lazily(LampBoardGen2, Loader(LampBackend))
    with pytest.raises(TypeError, match="LampBackend loaded for LampBoardGen2 drives LampBoard"):
        _ = env.backends


def test_a_backend_driving_a_subclass_is_known_by_it_once_loaded() -> None:
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(LampGen2Backend))  # declared by its family's class
    assert env.supported_boards == {LampBoard}
    assert env.backends_for(LampBoard) == (LampGen2Backend,)
    assert env.supported_boards == {LampBoardGen2}
    assert env.get_backend(LampBoardGen2) is LampGen2Backend


@pytest.mark.parametrize(
    ("board", "load", "message"),
    [
        (object, LampBackend, "board must be a Board subclass"),
        (LampBoard, "LampBackend", "load must be callable, not str"),
    ],
)
def test_register_lazily_checks_its_arguments(
    board: object, load: object, message: str
) -> None:
    with pytest.raises(TypeError, match=message):
        Environment("E").register_lazily(board, load)  # type: ignore[arg-type]


def test_registering_a_lazily_registered_backend_again_is_refused() -> None:
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(LampBackend))
    with pytest.raises(RuntimeError, match="already uses LampBackend for LampBoard"):
        env.register_backend(LampBackend, alongside=True)
    env.register_backend(LampGen2Backend)  # another board: no clash, nothing to compare


async def test_merging_keeps_backends_unloaded() -> None:
    load: Callable[[], type[Backend]] = Loader(LampBackend)
    first, second = Environment("First"), Environment("Second")
    second.register_lazily(LampBoard, load)
    first.merge(second)
    assert isinstance(load, Loader) and load.calls == 0
    assert len(await first.get_board_group(LampBoard)) == 2
    with pytest.raises(RuntimeError, match="both have a backend for LampBoard"):
        first.merge(second)


async def test_without_gathering_the_first_backend_of_the_class_asked_for_is_used() -> None:
    env = Environment("E", gather=False)
    env.register_lazily(LampBoard, Loader(LampBackend))
    env.register_lazily(LampBoardGen2, Loader(LampGen2Backend))
    assert [b.serial_number for b in await env.get_board_group(LampBoardGen2)] == ["C"]
    assert [b.serial_number for b in await env.get_board_group(LampBoard)] == ["A", "B"]

    only_gen2 = Environment("E2", gather=False)
    only_gen2.register_backend(LampGen2Backend)
    assert [b.serial_number for b in await only_gen2.get_board_group(LampBoard)] == ["C"]


# (beside this module, in the package it is imported as, so that its lamp board is ours)
LAZY_MODULE = f"{__package__}.lazy_lamp"


@pytest.fixture
def lazy_module_unloaded(monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    monkeypatch.delitem(sys.modules, LAZY_MODULE, raising=False)


def _lazy(name: str) -> type:
    found: type = getattr(importlib.import_module(LAZY_MODULE), name)
    return found


def _lazy_backend() -> type[Backend]:
    return _lazy("LazyLampBackend")


async def test_a_board_named_by_path_is_not_imported_while_its_backend_is_idle(
    lazy_module_unloaded: None,
) -> None:
    import sys

    idle = [True]
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(LampBackend))
    env._register_lazily_by_path(
        f"{LAZY_MODULE}:LazyLampBoard", _lazy_backend, idle=lambda: idle[0]
    )
    assert [board.serial_number for board in await env.get_board_group(LampBoard)] == ["A", "B"]
    assert not env.might_find(LampBoardGen2)
    assert env._has_backend_for(LampBoard)
    assert not env._has_backend_for(LampBoardGen2)
    assert LAZY_MODULE not in sys.modules  # idle: its class was never needed
    idle[0] = False
    assert env.might_find(LampBoard)
    group = await env.get_board_group(LampBoard)
    assert [board.serial_number for board in group] == ["A", "B", "L"]
    lazy_board = _lazy("LazyLampBoard")
    assert env._has_backend_for(lazy_board)
    assert lazy_board in env.supported_boards


def test_a_board_named_by_path_is_known_by_its_path_before_it_is_imported(
    lazy_module_unloaded: None,
) -> None:
    import sys

    env = Environment("E")
    env._register_lazily_by_path(f"{LAZY_MODULE}:LazyLampBoard", _lazy_backend)
    assert LAZY_MODULE not in sys.modules
    # Asking for another class imports it, to learn whether it is a subclass.
    assert not env.might_find(LampBoardGen2)
    assert env._has_backend_for(_lazy("LazyLampBoard"))
    assert env.get_backend(_lazy("LazyLampBoard")) is _lazy("LazyLampBackend")


def test_a_path_that_names_no_board_class_is_refused(lazy_module_unloaded: None) -> None:
    env = Environment("E")
    with pytest.raises(ValueError, match=r"must be named 'package\.module:ClassName'"):
        env._register_lazily_by_path("no path", _lazy_backend)
    with pytest.raises(TypeError, match="load must be callable"):
        env._register_lazily_by_path(f"{LAZY_MODULE}:LazyLampBoard", None)  # type: ignore[arg-type]
    env._register_lazily_by_path(f"{LAZY_MODULE}:NOT_A_BOARD", _lazy_backend)
    with pytest.raises(TypeError, match="is not a class"):
        env.might_find(LampBoard)
    env = Environment("E")
    env._register_lazily_by_path("builtins:int", _lazy_backend)
    with pytest.raises(TypeError, match="builtins:int is not a Board subclass"):
        env.might_find(LampBoard)


def test_might_find_named_imports_the_class_only_where_a_backend_may_find_one(
    lazy_module_unloaded: None,
) -> None:
    import sys

    path = f"{LAZY_MODULE}:LazyLampBoard"
    idle = [True]
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(LampBackend))
    env._register_lazily_by_path(path, _lazy_backend, idle=lambda: idle[0])
    assert not env._might_find_named(path)  # its only backend is idle
    assert LAZY_MODULE not in sys.modules
    idle[0] = False
    assert env._might_find_named(path)
    assert LAZY_MODULE in sys.modules
    idle[0] = True  # imported now: asked as might_find asks
    assert not env._might_find_named(path)
    assert env._might_find_named(f"{LampBoard.__module__}:LampBoard")


def test_might_find_named_refuses_what_names_no_board_class() -> None:
    env = Environment("E")
    env.register_lazily(LampBoard, Loader(LampBackend))
    with pytest.raises(ValueError, match="a board class must be named"):
        env._might_find_named("not a path")
    with pytest.raises(TypeError, match="builtins:int is not a Board subclass"):
        env._might_find_named("builtins:int")
