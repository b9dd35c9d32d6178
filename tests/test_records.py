"""FrozenRecord: a frozen dataclass's repr, equality and hash, from its fields."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import pytest

from j5aio._records import FrozenRecord
from tests.dataclass_twins import assert_like_generated


@dataclass(frozen=True, init=False, repr=False, eq=False)
class Point(FrozenRecord):
    x: float
    y: float = 0.0

    def __init__(self, x: float, y: float = 0.0) -> None:
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)


@dataclass(frozen=True, init=False, repr=False, eq=False)
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


def test_a_record_behaves_as_the_generated_dataclass() -> None:
    assert_like_generated(Point, [((1.0,), {}), ((1.0, 2.0), {}), ((), {"x": 3.0, "y": 4.0})])


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


def test_records_stay_frozen_dataclasses() -> None:
    point = Point(1.0, 2.0)
    assert dataclasses.replace(point, y=5.0) == Point(1.0, 5.0)
    assert dataclasses.asdict(point) == {"x": 1.0, "y": 2.0}
    with pytest.raises(dataclasses.FrozenInstanceError):
        point.x = 3.0  # type: ignore[misc]
