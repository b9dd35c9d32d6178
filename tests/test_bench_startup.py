"""bench/bench_startup.py's paired figure: each case minus the floor of its own round."""

from __future__ import annotations

import statistics
from types import ModuleType
from typing import Any

import pytest

from tests.module_from_file import ROOT, load_module


def load_bench() -> ModuleType:
    return load_module("bench_startup", ROOT / "bench" / "bench_startup.py")


BENCH = load_bench()


def _case(name: str, values: list[float]) -> Any:
    return BENCH.Case(name, ["python"], {}, list(values))


def test_each_round_is_set_against_its_own_floor() -> None:
    # The program is 20 ms above the floor of its round, except in two rounds where the
    # machine slowed it alone by 30 ms; in two others it slowed both by 40 ms. Set against
    # its own round's floor, the program is 20 ms above; the medians' difference says 50.
    floor = _case("floor", [0.060, 0.060, 0.060, 0.100, 0.100])
    program = _case("j5aio", [0.110, 0.110, 0.080, 0.120, 0.120])
    assert BENCH.paired_above(program, floor) == pytest.approx((0.020, 0.020, 0.050))
    assert program.median - floor.median == pytest.approx(0.050)


def test_the_middle_is_the_median_of_the_differences_and_the_quartiles_bound_it() -> None:
    floor = _case("floor", [0.060] * 7)
    program = _case("j5aio", [0.081, 0.079, 0.095, 0.080, 0.083, 0.078, 0.082])
    low, middle, high = BENCH.paired_above(program, floor)
    differences = [value - 0.060 for value in program.values]
    assert middle == pytest.approx(statistics.median(differences))
    assert low <= middle <= high
    assert high < 0.035  # one slow round (+ 35 ms) does not move the upper quartile there


def test_one_round_gives_its_difference_three_times() -> None:
    paired = BENCH.paired_above(_case("j5aio", [0.085]), _case("floor", [0.060]))
    assert paired == pytest.approx((0.025, 0.025, 0.025))


def test_cases_of_different_round_counts_are_refused() -> None:
    with pytest.raises(ValueError):
        BENCH.paired_above(_case("j5aio", [0.08, 0.09]), _case("floor", [0.06]))
