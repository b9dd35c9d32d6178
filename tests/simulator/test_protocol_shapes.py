"""The simulated kit's quick shape checks say what ``isinstance`` with their protocols says."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from j5aio.board_kinds import simulator_entries
from j5aio.simulator.clock import ClockedSimulator, ManualClock, _keeps_time
from j5aio.simulator.wiring import PowerBoardSimulator, PowerFed, is_power_board, is_power_fed


def _every_simulator() -> list[object]:
    made = []
    for name, (_kind, entry) in simulator_entries().items():
        try:
            made.append(entry.factory(f"SIM{name.upper().replace('-', '')}0"))
        except ImportError:  # (a plugin's simulator needing an extra not installed)
            continue
    return made


class _Shape:
    """An object with some members of the protocols, and some set to None."""

    def __init__(self, **members: Any) -> None:
        for name, value in members.items():
            setattr(self, name, value)


def _partial_shapes() -> list[object]:
    def method() -> None: ...

    return [
        object(),
        _Shape(clock=ManualClock()),
        _Shape(clock=ManualClock(), use_clock=method),
        _Shape(clock=ManualClock(), use_clock=None),
        _Shape(use_clock=method),
        _Shape(powered=True, supply_current=method),
        _Shape(powered=True, supply_current=method, listen=method),
        _Shape(powered=True, supply_current=None, listen=method),
        _Shape(OUTPUT_COUNT=7, outputs=(), set_supplied_current=method, trip_output=method),
        _Shape(
            OUTPUT_COUNT=7,
            outputs=(),
            set_supplied_current=method,
            trip_output=method,
            listen=method,
        ),
        _Shape(
            OUTPUT_COUNT=7,
            outputs=(),
            set_supplied_current=method,
            trip_output=None,
            listen=method,
        ),
    ]


@pytest.mark.parametrize(
    ("check", "protocol"),
    [
        (_keeps_time, ClockedSimulator),
        (is_power_fed, PowerFed),
        (is_power_board, PowerBoardSimulator),
    ],
)
def test_a_quick_check_agrees_with_isinstance(
    check: Callable[[object], bool], protocol: type
) -> None:
    candidates = [*_every_simulator(), *_partial_shapes()]
    answers = [check(candidate) for candidate in candidates]
    assert answers == [isinstance(candidate, protocol) for candidate in candidates]
    assert True in answers and False in answers  # (both answers are tried)
