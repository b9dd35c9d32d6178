"""Records: dataclasses that take their frozenness, repr, equality and hash from one base."""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle
from dataclasses import dataclass, field
from typing import Any

import pytest

from j5aio import _records
from j5aio._records import FrozenRecord, Record, frozen_record
from tests.dataclass_twins import assert_like_generated


@frozen_record
class Point(FrozenRecord):
    x: float
    y: float = 0.0

    def __init__(self, x: float, y: float = 0.0) -> None:
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)


@frozen_record
class Labelled(FrozenRecord):
    name: str
    note: str = field(default="", compare=False)
    secret: str = field(default="", repr=False)
    weight: int = field(default=0, hash=False)

    def __init__(self, name: str, note: str = "", secret: str = "", weight: int = 0) -> None:
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "note", note)
        object.__setattr__(self, "secret", secret)
        object.__setattr__(self, "weight", weight)


@dataclass(init=False, repr=False, eq=False)
class Counter(Record):
    """A mutable record."""

    name: str
    count: int = 0

    def __init__(self, name: str, count: int = 0) -> None:
        self.name = name
        self.count = count


@dataclass
class PlainCounter:  # what @dataclass alone makes of Counter's fields
    name: str
    count: int = 0


class PointSubclass(Point):
    """Not a dataclass itself: only the fields it inherits are frozen."""


@dataclass(frozen=True)
class PlainPoint:  # what @dataclass(frozen=True) alone makes of Point's fields
    x: float
    y: float = 0.0


class PlainPointSubclass(PlainPoint):
    pass


def test_a_record_behaves_as_the_generated_dataclass() -> None:
    assert_like_generated(Point, [((1.0,), {}), ((1.0, 2.0), {}), ((), {"x": 3.0, "y": 4.0})])
    assert_like_generated(Labelled, [(("a",), {}), (("a", "n", "s", 2), {}), (("b",), {})])


@dataclass(frozen=True)
class PlainLabelled:  # what @dataclass alone makes of Labelled's fields
    name: str
    note: str = field(default="", compare=False)
    secret: str = field(default="", repr=False)
    weight: int = field(default=0, hash=False)


def test_field_options_are_kept_as_dataclass_keeps_them() -> None:
    plain = PlainLabelled
    a, b = Labelled("a", note="one", secret="s", weight=1), Labelled("a", note="two", weight=2)
    twin_a, twin_b = plain("a", note="one", secret="s", weight=1), plain("a", note="two", weight=2)
    assert repr(a) == repr(twin_a).replace("PlainLabelled", "Labelled")
    assert repr(a) == "Labelled(name='a', note='one', weight=1)"
    assert (a == b) == (twin_a == twin_b)  # the note is not compared; the weight is
    assert a != b
    assert hash(Labelled("a", weight=1)) == hash(Labelled("a", weight=2))  # weight not hashed
    assert hash(Labelled("a", weight=1)) == hash(plain("a", weight=1))


def test_equality_is_that_of_the_fields_tuples() -> None:
    nan = math.nan
    assert Point(nan) == Point(nan)  # the same object in both: equal, as in a tuple
    assert Point(1.0) != Point(1.0, 1.0)
    assert Point(1.0).__eq__((1.0, 0.0)) is NotImplemented


def test_records_stay_dataclasses() -> None:
    assert dataclasses.is_dataclass(Point(0.0))
    point = Point(1.0, 2.0)
    assert [spec.name for spec in dataclasses.fields(point)] == ["x", "y"]
    assert dataclasses.replace(point, y=5.0) == Point(1.0, 5.0)
    assert dataclasses.asdict(point) == {"x": 1.0, "y": 2.0}
    assert dataclasses.astuple(point) == (1.0, 2.0)
    assert Point.__match_args__ == ("x", "y")
    match point:
        case Point(x, y):
            assert (x, y) == (1.0, 2.0)
        case _:  # pragma: no cover - the case above matches
            pytest.fail("a record should match by position")


@pytest.mark.parametrize(
    ("action", "plain_action"),
    [
        (lambda point: setattr(point, "x", 3.0), lambda plain: setattr(plain, "x", 3.0)),
        (lambda point: setattr(point, "z", 3.0), lambda plain: setattr(plain, "z", 3.0)),
        (lambda point: delattr(point, "y"), lambda plain: delattr(plain, "y")),
        (lambda point: delattr(point, "z"), lambda plain: delattr(plain, "z")),
    ],
    ids=["assign a field", "assign another name", "delete a field", "delete another name"],
)
def test_a_record_refuses_changes_as_a_frozen_dataclass_does(action, plain_action) -> None:  # type: ignore[no-untyped-def]
    point, plain = Point(1.0, 2.0), PlainPoint(1.0, 2.0)
    with pytest.raises(dataclasses.FrozenInstanceError) as expected:
        plain_action(plain)
    with pytest.raises(dataclasses.FrozenInstanceError) as refused:
        action(point)
    assert str(refused.value) == str(expected.value)
    assert str(refused.value).startswith("cannot ")
    assert vars(point) == {"x": 1.0, "y": 2.0}


def test_a_subclass_that_is_no_dataclass_freezes_only_the_fields() -> None:
    point, plain = PointSubclass(1.0), PlainPointSubclass(1.0)
    objects: tuple[Any, ...] = (point, plain)
    for obj in objects:
        obj.label = "here"
        assert obj.label == "here"
        del obj.label
        assert not hasattr(obj, "label")
        with pytest.raises(dataclasses.FrozenInstanceError, match="cannot assign to field 'x'"):
            obj.x = 2.0
        with pytest.raises(dataclasses.FrozenInstanceError, match="cannot delete field 'y'"):
            del obj.y
    assert repr(point) == "PointSubclass(x=1.0, y=0.0)"


def test_records_copy_and_pickle() -> None:
    point = Labelled("a", note="n", secret="s", weight=3)
    for made in (
        copy.copy(point),
        copy.deepcopy(point),
        pickle.loads(pickle.dumps(point)),
        pickle.loads(pickle.dumps(point, protocol=0)),
    ):
        assert made is not point
        assert type(made) is Labelled
        assert dataclasses.asdict(made) == dataclasses.asdict(point)
        with pytest.raises(dataclasses.FrozenInstanceError):
            made.name = "b"  # type: ignore[misc]


def test_a_mutable_record_behaves_as_the_generated_dataclass() -> None:
    counter, plain = Counter("a"), PlainCounter("a")
    assert repr(counter) == repr(plain).replace("PlainCounter", "Counter")
    counter.count += 2
    plain.count += 2
    assert repr(counter) == "Counter(name='a', count=2)"
    assert counter == Counter("a", 2) and counter != Counter("a", 3)
    assert counter.__eq__(plain) is NotImplemented
    for obj in (counter, plain):
        with pytest.raises(TypeError, match="unhashable type"):
            hash(obj)
    assert dataclasses.replace(counter, name="b") == Counter("b", 2)
    assert dataclasses.asdict(counter) == dataclasses.asdict(plain)
    assert copy.copy(counter) == counter and pickle.loads(pickle.dumps(counter)) == counter


def test_frozen_record_wants_a_frozen_record_with_its_own_init() -> None:
    class NotARecord:
        x: int

        def __init__(self, x: int) -> None:
            self.x = x

    class NoInit(FrozenRecord):
        x: int

    with pytest.raises(TypeError, match="makes FrozenRecord subclasses"):
        frozen_record(NotARecord)
    with pytest.raises(TypeError, match="NoInit must define __init__"):
        frozen_record(NoInit)


def test_a_record_says_it_is_frozen_and_so_can_be_subclassed_as_a_frozen_dataclass() -> None:
    assert Point.__dataclass_params__.frozen  # type: ignore[attr-defined]

    @dataclass(frozen=True)
    class Point3(Point):
        z: float = 0.0

    point = Point3(1.0, 2.0, 3.0)
    assert repr(point).endswith("Point3(x=1.0, y=2.0, z=3.0)")
    assert point == Point3(1.0, 2.0, 3.0) != Point3(1.0, 2.0)
    assert hash(point) == hash((1.0, 2.0, 3.0))
    with pytest.raises(dataclasses.FrozenInstanceError, match="cannot assign to field 'x'"):
        point.x = 0.0  # type: ignore[misc]
    # As of any frozen dataclass, a mutable one cannot be made of it.
    with pytest.raises(TypeError, match="cannot inherit non-frozen dataclass from a frozen one"):

        @dataclass
        class Mutable(Point):  # type: ignore[misc]
            z: float = 0.0


def test_a_record_whose_parameters_cannot_say_so_still_works_frozen() -> None:
    class FixedParameters:  # (a Python whose dataclass parameters cannot be changed)
        __slots__ = ()
        frozen = False

    class Fixed(FrozenRecord):
        __dataclass_params__ = FixedParameters()
        x: int

        def __init__(self, x: int) -> None:
            object.__setattr__(self, "x", x)

    _records._say_frozen(Fixed)  # does not raise
    assert Fixed.__dataclass_params__.frozen is False
    made = frozen_record(Fixed)  # (the decorator makes its own parameters, which it can change)
    assert made.__dataclass_params__.frozen
    with pytest.raises(dataclasses.FrozenInstanceError):
        made(1).x = 2
