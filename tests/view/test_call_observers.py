"""The observer hook of the backend wrapper: every interface call, its result or error."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from typing import Any

import pytest

from j5aio.backends.backend import CALL_OBSERVERS
from j5aio.errors import CommunicationError
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit


@pytest.fixture
def calls() -> Iterator[list[tuple[Any, ...]]]:
    seen: list[tuple[Any, ...]] = []

    def observer(*call: Any) -> None:
        seen.append(call)

    CALL_OBSERVERS.append(observer)
    try:
        yield seen
    finally:
        CALL_OBSERVERS.remove(observer)


async def test_observers_see_calls_results_and_errors(calls: list[tuple[Any, ...]]) -> None:
    kit = use_kit(KitConfig(motor_boards=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        motor = robot.motor_boards[0].motors[1]
        calls.clear()
        await motor.set_power(0.5)
        assert calls == [(robot.motor_boards[0].backend, "set_motor_state", (1, 0.5), None, None)]
        calls.clear()
        assert await motor.get_power() == 0.5
        assert calls[-1][1:] == ("get_motor_state", (1,), 0.5, None)
        # keyword arguments arrive in the interface's order
        calls.clear()
        backend: Any = robot.motor_boards[0].backend
        await backend.set_motor_state(power=0.25, identifier=0)
        assert calls[-1][1:] == ("set_motor_state", (0, 0.25), None, None)
        # a failing call is seen with its error, then raised as before
        kit.motor_boards[0].unplug()
        calls.clear()
        with pytest.raises(CommunicationError):
            await motor.set_power(0.1)
        assert calls and isinstance(calls[-1][4], CommunicationError)
        kit.motor_boards[0].plug()


async def test_a_failing_observer_is_logged_and_ignored(
    calls: list[tuple[Any, ...]], caplog: pytest.LogCaptureFixture
) -> None:
    def broken(*call: Any) -> None:
        raise RuntimeError("observer bug")

    use_kit(KitConfig(motor_boards=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        CALL_OBSERVERS.insert(0, broken)
        try:
            with caplog.at_level(logging.ERROR):
                await robot.motor_boards[0].motors[0].set_power(0.3)
        finally:
            CALL_OBSERVERS.remove(broken)
        assert "call observer" in caplog.text and "observer bug" in caplog.text
        assert calls[-1][1] == "set_motor_state"  # the next observer was still told
