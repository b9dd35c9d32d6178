"""The simulated clocks: scaled real time, manual time, and a board's own time."""

from __future__ import annotations

import math

import pytest

from j5aio.simulator.clock import (
    BoardTime,
    ClockedSimulator,
    ManualClock,
    ScaledClock,
    drive,
    kit_clock,
)
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator


class FakeMonotonic:
    """A stand-in for time.monotonic that a test moves on."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_a_scaled_clock_divides_real_time_by_its_scale() -> None:
    real = FakeMonotonic()
    clock = ScaledClock(2.0, source=real)
    assert clock.now() == 0
    real.now += 3
    assert clock.now() == pytest.approx(1.5)
    assert clock.time_scale == 2.0
    assert "x2" in repr(clock)


@pytest.mark.parametrize(
    ("scale", "error", "message"),
    [
        (0, ValueError, "time would stand still"),
        (-1, ValueError, "0 or more"),
        (math.nan, ValueError, "finite"),
        (math.inf, ValueError, "finite"),
        ("1", TypeError, "not str"),
        (True, TypeError, "not bool"),
    ],
)
def test_a_scaled_clock_refuses_a_bad_scale(scale: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        ScaledClock(scale)  # type: ignore[arg-type]


def test_the_kit_clock_runs_at_real_time_for_a_scale_of_zero() -> None:
    assert kit_clock(0).time_scale == 1.0
    assert kit_clock(0.5).time_scale == 0.5
    assert kit_clock(3).time_scale == 3.0
    with pytest.raises(ValueError, match="0 or more"):
        kit_clock(-0.1)


def test_the_real_clock_moves_forwards() -> None:
    clock = ScaledClock()
    first = clock.now()
    assert clock.now() >= first >= 0


def test_a_manual_clock_stands_still_until_advanced() -> None:
    clock = ManualClock(5)
    assert clock.now() == 5
    clock.advance(0.25)
    assert clock.now() == 5.25
    assert "5.25" in repr(clock)
    with pytest.raises(ValueError, match="0 or more"):
        clock.advance(-1)
    with pytest.raises(TypeError, match="number of seconds"):
        clock.advance(None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="finite"):
        ManualClock(math.inf)


def test_board_time_counts_exact_milliseconds_from_added_up_steps() -> None:
    clock = ManualClock()
    board = BoardTime(clock)
    for _ in range(3):
        clock.advance(0.1)  # 0.30000000000000004 s in floating point
    assert board.milliseconds() == 300
    board.skip(0.0005)
    assert board.milliseconds() == 300
    assert board.seconds() == pytest.approx(0.3005)
    with pytest.raises(ValueError, match="0 or more"):
        board.skip(-0.1)


def test_board_time_keeps_its_time_across_a_change_of_clock() -> None:
    first, second = ManualClock(), ManualClock(1000)
    board = BoardTime(first)
    first.advance(2)
    board.follow(second)
    assert board.clock is second
    assert board.seconds() == 2  # the new clock's reading is not a jump
    first.advance(5)  # the old clock no longer counts
    second.advance(1)
    assert board.seconds() == 3


def test_board_time_ignores_a_clock_that_goes_back() -> None:
    real = FakeMonotonic()
    board = BoardTime(ScaledClock(source=real))
    real.now += 1
    assert board.seconds() == 1
    real.now -= 0.5
    assert board.seconds() == 1
    real.now += 1  # on again from where it went back to: only the new time counts
    assert board.seconds() == 1.5


def test_board_time_stands_still_without_a_clock() -> None:
    board = BoardTime()
    assert isinstance(board.clock, ManualClock)
    assert board.milliseconds() == 0


def test_drive_gives_the_clock_to_the_simulators_that_keep_time() -> None:
    clock = ManualClock()
    fw4 = SRPowerBoardFw4Simulator("SIMPB0")
    fw3 = SRPowerBoardFw3Simulator("SIMPB1")
    servo = SRServoBoardFw2Simulator("SIMSB0")
    assert isinstance(fw4, ClockedSimulator) and isinstance(fw3, ClockedSimulator)
    assert not isinstance(servo, ClockedSimulator)
    drive([fw4, fw3, servo, object()], clock)
    assert fw4.clock is clock and fw3.clock is clock
