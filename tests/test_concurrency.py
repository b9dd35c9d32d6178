"""Tests of at_once: several requests at the same time, their answers in order."""

from __future__ import annotations

import asyncio
import contextvars
import gc
import warnings
from collections.abc import Awaitable, Generator
from typing import Any

import anyio
import anyio.lowlevel
import pytest

from j5aio.components.motor import MotorSpecialState
from j5aio.concurrency import at_once
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode


async def answer(value: object, *, after: float = 0) -> object:
    await asyncio.sleep(after)
    return value


async def fail(error: BaseException, *, after: float = 0) -> None:
    await asyncio.sleep(after)
    raise error


class Cleanup:
    """A request that runs until cancelled, then takes a few turns of the loop to stop."""

    def __init__(self) -> None:
        self.started = False
        self.running = asyncio.Event()
        self.cancelled = False
        self.stopped = False

    async def run(self) -> None:
        self.started = True
        self.running.set()
        try:
            await asyncio.sleep(3600)
        except asyncio.CancelledError:
            self.cancelled = True
            with anyio.CancelScope(shield=True):
                for _ in range(5):  # a clean-up that talks to a board takes a while
                    await anyio.lowlevel.checkpoint()
            raise
        finally:
            self.stopped = True


async def test_the_answers_come_back_in_the_order_of_the_requests() -> None:
    results = await at_once(answer("slow", after=0.02), answer(2), answer(None, after=0.01))
    assert results == ("slow", 2, None)


async def test_no_requests_give_no_answers() -> None:
    assert await at_once() == ()


async def test_the_requests_run_at_the_same_time() -> None:
    # Each request waits for the other: made one after another they would wait forever.
    first_here, second_here = asyncio.Event(), asyncio.Event()

    async def meet(mine: asyncio.Event, theirs: asyncio.Event, name: str) -> str:
        mine.set()
        await theirs.wait()
        return name

    with anyio.fail_after(5):
        assert await at_once(
            meet(first_here, second_here, "a"), meet(second_here, first_here, "b")
        ) == ("a", "b")


async def test_a_failure_cancels_the_others_and_waits_for_them_before_it_is_raised() -> None:
    long = Cleanup()
    with anyio.move_on_after(5) as scope:
        with pytest.raises(KeyError, match="battery") as raised:
            await at_once(long.run(), fail(KeyError("battery"), after=0.01), answer(1))
    assert not scope.cancel_called  # at_once cancelled the long request, not the time limit
    assert long.started and long.cancelled and long.stopped
    assert not getattr(raised.value, "__notes__", None)


async def test_a_shielded_clean_up_under_way_is_not_broken_into() -> None:
    # at_once stops a request through anyio, as a task group would: Task.cancel() would
    # break through the shield of a brake already being applied.
    braked: list[str] = []

    async def braking() -> None:
        with anyio.CancelScope(shield=True):
            await anyio.sleep(0.05)  # the brake's request, on its way
            braked.append("left")
        await anyio.sleep(3600)

    with pytest.raises(KeyError, match="servo"):
        await at_once(braking(), fail(KeyError("servo"), after=0.01))
    assert braked == ["left"]


async def test_a_request_stopped_before_its_turn_never_starts() -> None:
    started: list[str] = []

    async def request() -> None:
        started.append("request")

    async def fails_at_once() -> None:
        raise KeyError("power board")

    with pytest.raises(KeyError, match="power board"):
        # The first request fails before the second has had its first turn.
        await at_once(fails_at_once(), request())
    assert started == []


async def test_failures_at_the_same_moment_raise_the_first_and_name_the_others() -> None:
    async def fail_shielded(error: BaseException) -> None:
        with anyio.CancelScope(shield=True):  # (so that the first failure cannot stop it)
            await asyncio.sleep(0)
            raise error

    with pytest.raises(ValueError, match="first") as raised:
        await at_once(fail(ValueError("first")), fail_shielded(OSError("second")))
    assert raised.value.__notes__ == [
        "at_once(): other requests failed at the same time: OSError: second"
    ]


async def test_a_cancelled_caller_cancels_every_request_and_waits_until_each_has_stopped() -> None:
    requests = [Cleanup(), Cleanup()]
    with anyio.move_on_after(0.01) as scope:
        await at_once(*(request.run() for request in requests), answer("fast"))
    assert scope.cancelled_caught
    # anyio repeats the cancellation while the caller waits; at_once still waited for
    # the shielded clean-ups to end.
    assert all(request.cancelled and request.stopped for request in requests)


async def test_an_error_raised_while_being_cancelled_is_not_lost() -> None:
    async def breaks_when_cancelled() -> None:
        try:
            await asyncio.sleep(3600)
        finally:
            raise RuntimeError("the motor board did not answer while braking")

    with pytest.raises(RuntimeError, match="while braking"), anyio.move_on_after(0.01):
        await at_once(breaks_when_cancelled())


async def test_asyncio_timeout_around_it_becomes_a_timeout_error() -> None:
    request = Cleanup()
    with pytest.raises(TimeoutError):
        async with asyncio.timeout(0.01):
            await at_once(request.run())
    assert request.stopped
    assert asyncio.current_task().cancelling() == 0  # type: ignore[union-attr]


async def test_a_caller_cancelled_by_task_cancel_is_cancelled() -> None:
    request = Cleanup()
    caller = asyncio.ensure_future(at_once(request.run()))
    await request.running.wait()
    caller.cancel()
    with pytest.raises(asyncio.CancelledError):
        await caller
    assert request.stopped


async def test_futures_tasks_and_other_awaitables_are_requests_too() -> None:
    class Awaitable42:
        def __await__(self) -> Generator[Any, None, int]:
            yield from asyncio.sleep(0).__await__()
            return 42

    future: asyncio.Future[str] = asyncio.get_running_loop().create_future()
    future.set_result("done")
    task = asyncio.ensure_future(answer("task"))
    assert await at_once(future, task, Awaitable42()) == ("done", "task", 42)


async def test_each_request_sees_the_callers_context() -> None:
    setting: contextvars.ContextVar[str] = contextvars.ContextVar("setting", default="unset")

    async def read_setting() -> str:
        return setting.get()

    setting.set("the caller's")
    assert await at_once(read_setting(), read_setting()) == ("the caller's", "the caller's")


@pytest.mark.parametrize(
    ("make_bad", "says"),
    [
        (lambda: answer, "argument 2 is answer itself, not a request: call it (answer(...))"),
        (lambda: 12.5, "argument 2 is float 12.5, which cannot be awaited: pass the call"),
        (lambda: None, "argument 2 is NoneType None, which cannot be awaited: pass the call"),
    ],
)
async def test_something_that_cannot_be_awaited_is_refused_and_nothing_starts(
    make_bad: Any, says: str
) -> None:
    started: list[str] = []

    async def request() -> None:
        started.append("request")

    message = ""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            await at_once(request(), make_bad(), request())
        except TypeError as error:  # (the error, and the requests its frames hold, go here)
            message = str(error)
        gc.collect()
    assert says in message
    assert ("at_once is for async code" in message) is (make_bad() is None)
    assert "at_once() takes requests to make" in message
    assert started == []
    # The requests given were closed, never started: no "was never awaited" warning.
    assert not [w for w in caught if "never awaited" in str(w.message)]


async def test_four_boards_of_the_simulated_kit_at_once(fresh_kit: None) -> None:
    kit = use_kit(KitConfig(ruggeduinos=0))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        motor = robot.motor_boards[0].motors[0]
        requests: list[Awaitable[object]] = [
            robot.power_board.battery_sensor.get_voltage(),
            motor.set_power(0.5),
            robot.servo_boards[0].servos[0].set_position(-0.25),
            robot.arduinos[0].pins[3].digital_read(),
        ]
        voltage, set_result, position_result, pin = await at_once(*requests)
        assert isinstance(voltage, float) and voltage > 0
        assert set_result is None and position_result is None
        assert isinstance(pin, bool)
        assert await motor.get_power() == 0.5
        assert kit.motor_boards[0].motors[0].mode is MotorMode.FORWARD
        await motor.set_power(MotorSpecialState.BRAKE)
