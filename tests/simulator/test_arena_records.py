"""The arena's small records behave as the frozen dataclasses they stand in for."""

from __future__ import annotations

import copy
import math
import pickle
from dataclasses import FrozenInstanceError
from typing import Any

import pytest

from j5aio.simulator.arena import Arena, ArenaMarker, DifferentialDrive, Pose, Token

RECORDS: list[tuple[Any, Any, Any, str]] = [
    (
        Arena(markers=(ArenaMarker(3, 150.0, 1.0, 2.0, 250.0, 0.0),)),
        Arena(5750.0, 5750.0, 500.0, (ArenaMarker(3, 150.0, 1.0, 2.0, 250.0, 0.0),), ()),
        Arena(),
        "Arena(width=5750.0, length=5750.0, wall_height=500.0, markers=(ArenaMarker(marker_id=3, "
        "size=150.0, x=1.0, y=2.0, z=250.0, facing=0.0),), tokens=())",
    ),
    (
        Pose(1.0, 2.0, 0.5), Pose(1.0, 2.0, 0.5), Pose(1.0, 2.0, 0.25),
        "Pose(x=1.0, y=2.0, heading=0.5)",
    ),
    (
        ArenaMarker(3, 150.0, 1.0, 2.0, 250.0, math.pi),
        ArenaMarker(3, 150.0, 1.0, 2.0, 250.0, math.pi),
        ArenaMarker(4, 150.0, 1.0, 2.0, 250.0, math.pi),
        "ArenaMarker(marker_id=3, size=150.0, x=1.0, y=2.0, z=250.0, facing=3.141592653589793)",
    ),
    (
        Token(100, 1.0, 2.0), Token(100, 1.0, 2.0, side=130.0), Token(100, 1.0, 2.0, side=99.0),
        "Token(marker_id=100, x=1.0, y=2.0, side=130.0, marker_size=80.0, heading=0.0)",
    ),
    (
        DifferentialDrive(), DifferentialDrive(max_speed=1000.0), DifferentialDrive(radius=5.0),
        "DifferentialDrive(left=(0, 0), right=(0, 1), max_speed=1000.0, track_width=300.0, "
        "radius=200.0)",
    ),
]


@pytest.mark.parametrize(("record", "same", "other", "shown"), RECORDS)
def test_a_record_is_equal_hashed_and_shown_by_its_fields(
    record: Any, same: Any, other: Any, shown: str,
) -> None:
    assert record == same and hash(record) == hash(same)
    assert record != other
    assert record != tuple(getattr(record, name) for name in record._fields)  # not a tuple
    assert repr(record) == shown
    assert pickle.loads(pickle.dumps(record)) == record
    assert copy.copy(record) is record and copy.deepcopy(record) is record


@pytest.mark.parametrize(("record", "same", "other", "shown"), RECORDS)
def test_a_record_cannot_be_changed(record: Any, same: Any, other: Any, shown: str) -> None:
    name = record._fields[0]
    with pytest.raises(FrozenInstanceError, match=f"cannot assign to field {name!r}"):
        setattr(record, name, 1)
    with pytest.raises(FrozenInstanceError, match="cannot delete field"):
        delattr(record, name)
    with pytest.raises(FrozenInstanceError):
        record.not_a_field = 1
    assert record == same


def test_a_pose_is_not_equal_to_another_kind_of_record() -> None:
    token: object = Token(1, 2.0, 3.0)
    assert Pose(1.0, 2.0, 3.0) != token
    assert Pose(1.0, 2.0, 3.0).__eq__(object()) is NotImplemented
