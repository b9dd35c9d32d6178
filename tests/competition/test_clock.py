"""Tests of the robot's (scalable) clock."""

from __future__ import annotations

import time

import pytest

from j5aio.competition.clock import TIME_SCALE_VARIABLE, MatchClock, time_scale_from_environment


def test_scale_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(TIME_SCALE_VARIABLE, raising=False)
    assert time_scale_from_environment() == 1.0
    monkeypatch.setenv(TIME_SCALE_VARIABLE, "0.5")
    assert time_scale_from_environment() == 0.5
    assert MatchClock().scale == 0.5
    for bad in ("0", "-1", "fast", "nan", "inf"):
        monkeypatch.setenv(TIME_SCALE_VARIABLE, bad)
        with pytest.raises(ValueError, match="J5AIO_TIME_SCALE must be a number more than 0"):
            time_scale_from_environment()


def test_bad_scales_are_refused() -> None:
    with pytest.raises(TypeError):
        MatchClock(True)
    with pytest.raises(ValueError):
        MatchClock(0)


async def test_robot_time_runs_at_the_scale() -> None:
    clock = MatchClock(0.1)  # ten robot seconds per real second
    assert clock.to_real(3) == pytest.approx(0.3)
    started = time.monotonic()
    await clock.sleep(1.0)
    real = time.monotonic() - started
    assert 0.09 <= real < 1.0  # liveness: a robot second took about 0.1 s
    assert clock.time() >= 1.0


async def test_sleep_checks_its_argument() -> None:
    clock = MatchClock(1)
    with pytest.raises(TypeError, match="sleep time"):
        await clock.sleep("1")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="sleep time"):
        await clock.sleep(-1)
