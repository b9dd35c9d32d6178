"""wrap / unwrap: the same wrapper for the same core object, lazy views of containers."""

from __future__ import annotations

import gc
import subprocess
import sys
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

import pytest

from j5aio.numbered import NumberedComponents, Pins
from j5aio.sync import wrapping as _wrapping
from j5aio.sync.wrapping import (
    SyncWrapper,
    WrappedMapping,
    WrappedSequence,
    adopt,
    register,
    register_later,
    unwrap,
    wrap,
    wrap_kept,
)

from .sync_fakes import ScriptedConsoleLog, motor_board


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


def test_a_wrapper_nobody_holds_is_forgotten_once_enough_newer_ones_were_made() -> None:
    core = CoreThing("short-lived")
    first = id(wrap(core))
    gc.collect()
    assert id(wrap(core)) == first  # kept for a while: reading it again finds the same one
    others = [CoreThing(str(number)) for number in range(_wrapping.RECENT_WRAPPERS)]
    for other in others:
        wrap(other)
    gc.collect()
    assert id(core) not in _wrapping._WRAPPERS
    assert isinstance(wrap(core), Thing)


class Owner:
    """A core object with fixed and changing collections, as boards have."""

    def __init__(self) -> None:
        self.things = (CoreThing("0"), CoreThing("1"))
        self.pins = Pins({2: CoreThing("pin 2"), 3: CoreThing("pin 3")}, owner="owner")
        self.motors = NumberedComponents([CoreThing("m0")], owner="owner", kind="motor")
        self.names = ["a", "b"]
        self.mixed = (CoreThing("x"), ["a list"])
        self.part = CoreThing("part")


class OwnerWrapper(SyncWrapper):
    __slots__ = ()


def test_fixed_collections_and_single_wrappers_are_kept_by_their_owner() -> None:
    owner = OwnerWrapper._from_core(Owner())
    core = owner._core
    for name in ("things", "pins", "motors", "part"):
        first = wrap_kept(owner, name, getattr(core, name))
        assert wrap_kept(owner, name, getattr(core, name)) is first, name
    assert wrap_kept(owner, "pins", core.pins)[3]._core is core.pins[3]
    assert wrap_kept(owner, "motors", core.motors)[0]._core is core.motors[0]
    # A new collection from the core object is wrapped afresh, and then kept in turn.
    core.things = (CoreThing("new"),)
    renewed = wrap_kept(owner, "things", core.things)
    assert renewed[0]._core is core.things[0]
    assert wrap_kept(owner, "things", core.things) is renewed


def test_collections_that_may_change_are_wrapped_afresh() -> None:
    owner = OwnerWrapper._from_core(Owner())
    core = owner._core
    names = wrap_kept(owner, "names", core.names)
    core.names.append("c")
    assert wrap_kept(owner, "names", core.names) == ["a", "b", "c"]
    assert names == ["a", "b"]
    mixed = wrap_kept(owner, "mixed", core.mixed)
    assert wrap_kept(owner, "mixed", core.mixed) is not mixed  # a tuple holding a list
    assert wrap_kept(owner, "leaf", 3) == 3


def test_generated_wrappers_keep_their_boards_collections() -> None:
    log = ScriptedConsoleLog()
    board = motor_board(log, "MB-kept")
    assert board.motors is board.motors
    assert board.motors[0] is board.motors[0]
    assert board.motors[0]._core is board._core.motors[0]


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


def test_a_class_registered_by_name_is_wrapped_once_its_module_is_imported(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    (tmp_path / "late_feature_for_wrapping.py").write_text("class Tracker:\n    pass\n")
    monkeypatch.syspath_prepend(str(tmp_path))

    class TrackerWrapper(SyncWrapper):
        __slots__ = ()

    register_later("late_feature_for_wrapping", "Tracker", TrackerWrapper)
    assert "late_feature_for_wrapping" not in sys.modules  # registering imported nothing
    try:
        import late_feature_for_wrapping  # type: ignore[import-not-found]

        tracker = late_feature_for_wrapping.Tracker()
        wrapper = wrap(tracker)
        assert type(wrapper) is TrackerWrapper
        assert unwrap(wrapper) is tracker
        assert unwrap(TrackerWrapper) is late_feature_for_wrapping.Tracker
    finally:
        _wrapping._PENDING.pop(TrackerWrapper, None)
        _wrapping._WRAPPER_CLASSES.pop(late_feature_for_wrapping.Tracker, None)
        _wrapping._CORE_CLASSES.pop(TrackerWrapper, None)
        sys.modules.pop("late_feature_for_wrapping", None)


def test_asking_for_the_core_class_of_a_wrapper_registered_by_name_imports_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    (tmp_path / "late_feature_for_unwrap.py").write_text("class Tracker:\n    pass\n")
    monkeypatch.syspath_prepend(str(tmp_path))

    class TrackerWrapper(SyncWrapper):
        __slots__ = ()

    class MyTrackerWrapper(TrackerWrapper):
        __slots__ = ()

    register_later("late_feature_for_unwrap", "Tracker", TrackerWrapper)
    try:
        core = _wrapping.core_class_of(MyTrackerWrapper)
        assert core is sys.modules["late_feature_for_unwrap"].Tracker
        assert _wrapping.registered()[core] is TrackerWrapper
    finally:
        _wrapping._PENDING.pop(TrackerWrapper, None)
        module = sys.modules.pop("late_feature_for_unwrap", None)
        if module is not None:
            _wrapping._WRAPPER_CLASSES.pop(module.Tracker, None)
        _wrapping._CORE_CLASSES.pop(TrackerWrapper, None)


def test_a_name_registered_for_a_wrapper_that_is_not_a_class_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    (tmp_path / "late_feature_not_a_class.py").write_text("Tracker = 3\n")
    monkeypatch.syspath_prepend(str(tmp_path))

    class TrackerWrapper(SyncWrapper):
        __slots__ = ()

    register_later("late_feature_not_a_class", "Tracker", TrackerWrapper)
    try:
        with pytest.raises(TypeError, match=r"late_feature_not_a_class\.Tracker"):
            _wrapping.registered()
    finally:
        _wrapping._PENDING.pop(TrackerWrapper, None)
        sys.modules.pop("late_feature_not_a_class", None)


def test_the_facade_does_not_import_the_vision_tracker() -> None:
    code = (
        "import sys\n"
        "from j5aio.sync import KitRobot, wrapping\n"
        "assert 'j5aio.vision.track' not in sys.modules, 'imported'\n"
        "from j5aio.sync import PositionTracker\n"
        "from j5aio.sync.wrapping import unwrap\n"
        "from j5aio.vision.track import PositionTracker as Core\n"
        "assert unwrap(PositionTracker) is Core\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)
