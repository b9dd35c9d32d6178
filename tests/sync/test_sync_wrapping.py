"""wrap / unwrap: the same wrapper for the same core object, lazy views of containers."""

from __future__ import annotations

import gc
from collections.abc import Iterator, Mapping, Sequence

from j5aio.sync import wrapping as _wrapping
from j5aio.sync.wrapping import (
    SyncWrapper,
    WrappedMapping,
    WrappedSequence,
    adopt,
    register,
    unwrap,
    wrap,
)


class CoreThing:
    def __init__(self, name: str) -> None:
        self.name = name

    def __str__(self) -> str:
        return f"thing {self.name}"

    def __repr__(self) -> str:
        return f"CoreThing({self.name!r})"


class SpecialCoreThing(CoreThing):
    pass


class Thing(SyncWrapper):
    __slots__ = ()


register(CoreThing, Thing)


class CoreSequence(Sequence[CoreThing]):
    def __init__(self, items: list[CoreThing]) -> None:
        self._items = items

    def __getitem__(self, index: int) -> CoreThing:  # type: ignore[override]
        return self._items[index]

    def __len__(self) -> int:
        return len(self._items)


def test_leaves_and_unknown_objects_come_back_unchanged() -> None:
    marker = object()
    for value in (1, 2.5, "text", b"bytes", None, True, marker, CoreThing):
        assert wrap(value) is value


def test_core_objects_get_one_wrapper_each() -> None:
    core = CoreThing("a")
    wrapper = wrap(core)
    assert isinstance(wrapper, Thing)
    assert wrapper._core is core
    assert wrap(core) is wrapper
    assert wrap(CoreThing("b")) is not wrapper
    assert str(wrapper) == "thing a"
    assert repr(wrapper) == "<sync CoreThing('a')>"


def test_subclasses_of_a_registered_class_use_its_wrapper() -> None:
    assert isinstance(wrap(SpecialCoreThing("s")), Thing)


def test_a_wrapper_nobody_holds_is_forgotten() -> None:
    core = CoreThing("short-lived")
    wrap(core)
    gc.collect()
    assert id(core) not in _wrapping._WRAPPERS
    assert isinstance(wrap(core), Thing)


def test_adopted_wrappers_are_the_ones_wrap_returns() -> None:
    core = CoreThing("adopted")
    wrapper = adopt(Thing, core)
    assert wrap(core) is wrapper


def test_lists_tuples_sets_and_iterators_are_wrapped_item_by_item() -> None:
    a, b = CoreThing("a"), CoreThing("b")
    as_list = wrap([a, b])
    assert isinstance(as_list, list)
    assert [t._core for t in as_list] == [a, b]
    as_tuple = wrap((a, 1))
    assert isinstance(as_tuple, tuple)
    assert as_tuple[0] is wrap(a)
    assert as_tuple[1] == 1
    assert wrap({a}) == {wrap(a)}
    assert wrap(frozenset({b})) == frozenset({wrap(b)})
    iterator = wrap(iter([a, b]))
    assert isinstance(iterator, Iterator)
    assert list(iterator) == [wrap(a), wrap(b)]


def test_mappings_are_wrapped_lazily() -> None:
    a = CoreThing("a")
    core: dict[str, CoreThing] = {"a": a}
    view = wrap(_ReadOnly(core))
    assert isinstance(view, WrappedMapping)
    assert isinstance(view, Mapping)
    assert view["a"] is wrap(a)
    assert list(view) == ["a"]
    assert len(view) == 1
    core["b"] = CoreThing("b")
    assert isinstance(view["b"], Thing)
    assert "_ReadOnly" in repr(view)


def test_sequences_are_wrapped_lazily() -> None:
    items = [CoreThing("a"), CoreThing("b"), CoreThing("c")]
    view = wrap(CoreSequence(items))
    assert isinstance(view, WrappedSequence)
    assert view[0] is wrap(items[0])
    assert view[-1] is wrap(items[2])
    assert [t._core for t in view[1:]] == items[1:]
    assert [t._core for t in view] == items
    assert len(view) == 3
    assert "CoreSequence" in repr(view)


def test_unwrap_gives_back_the_core_objects() -> None:
    a = CoreThing("a")
    wrapper = wrap(a)
    assert unwrap(wrapper) is a
    assert unwrap([wrapper, 1]) == [a, 1]
    assert unwrap((wrapper,)) == (a,)
    assert unwrap({"k": wrapper}) == {"k": a}
    sequence = CoreSequence([a])
    assert unwrap(wrap(sequence)) is sequence
    assert unwrap("plain") == "plain"


class _ReadOnly(Mapping[str, CoreThing]):
    def __init__(self, data: dict[str, CoreThing]) -> None:
        self._data = data

    def __getitem__(self, key: str) -> CoreThing:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return "_ReadOnly(...)"


def test_unwrap_turns_a_wrapper_class_into_its_core_class() -> None:
    from j5aio import sync
    from j5aio.boards.sr.v4 import MotorBoard

    class MyMotorBoard(sync.MotorBoard):
        __slots__ = ()

    assert unwrap(sync.MotorBoard) is MotorBoard
    assert unwrap(MyMotorBoard) is MotorBoard
    assert unwrap(MotorBoard) is MotorBoard
    assert unwrap(int) is int
    assert _wrapping.core_class_of(int) is None
    assert _wrapping.registered()[MotorBoard] is sync.MotorBoard


def test_a_late_registration_wins_over_what_was_found_for_a_subclass() -> None:
    from j5aio import sync
    from j5aio.boards.sr.v4 import MotorBoard

    class LateBoard(MotorBoard):
        pass

    class LateWrapper(sync.MotorBoard):
        __slots__ = ()

    assert _wrapping._wrapper_class_of(LateBoard) is sync.MotorBoard  # found via its base
    register(LateBoard, LateWrapper)
    try:
        assert _wrapping._wrapper_class_of(LateBoard) is LateWrapper
        assert unwrap(LateWrapper) is LateBoard
    finally:
        del _wrapping._WRAPPER_CLASSES[LateBoard]
        del _wrapping._CORE_CLASSES[LateWrapper]
