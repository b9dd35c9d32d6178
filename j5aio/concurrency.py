"""Several requests at once, their answers in order: :func:`at_once`.

A control loop that reads the battery, sets a motor and reads a pin waits for each board
in turn when it awaits one request after another. Requests to different boards can be
on their wires at the same time instead; ``at_once`` sends them together and gives back
every answer, in the order the requests were given::

    voltage, _, pin_high = await at_once(
        robot.power_board.battery_sensor.get_voltage(),
        robot.motor_boards[0].motors[0].set_power(0.5),
        robot.arduinos[0].pins[3].digital_read(),
    )

The loop then takes as long as its slowest board, not the sum of them all. (Requests to
one board still go in the order given: a board answers one request at a time.)

Use ``at_once`` for requests whose answers the code needs now, and a task group
(``anyio.create_task_group()``) for behaviours that run for a while side by side (drive,
blink, watch). Both are cancelled as one: when the code awaiting ``at_once`` is cancelled
(a ``move_on_after`` scope running out, a task group cancelled, Ctrl-C), every request
still running is cancelled and ``at_once`` waits until each has stopped before it lets
the cancellation through; nothing is left running behind the caller's back. Requests are
stopped as a task group stops its tasks, through anyio cancel scopes: a clean-up a
request runs under ``anyio.CancelScope(shield=True)`` (braking, say) is not broken into.
"""

from __future__ import annotations

import asyncio
import inspect
from collections.abc import Awaitable
from types import CoroutineType
from typing import Any, TypeVar, overload

import anyio

__all__ = ["at_once"]

_T1 = TypeVar("_T1")
_T2 = TypeVar("_T2")
_T3 = TypeVar("_T3")
_T4 = TypeVar("_T4")
_T5 = TypeVar("_T5")
_T6 = TypeVar("_T6")


@overload
async def at_once() -> tuple[()]: ...
@overload
async def at_once(first: Awaitable[_T1], /) -> tuple[_T1]: ...
@overload
async def at_once(first: Awaitable[_T1], second: Awaitable[_T2], /) -> tuple[_T1, _T2]: ...
@overload
async def at_once(
    first: Awaitable[_T1], second: Awaitable[_T2], third: Awaitable[_T3], /
) -> tuple[_T1, _T2, _T3]: ...
@overload
async def at_once(
    first: Awaitable[_T1],
    second: Awaitable[_T2],
    third: Awaitable[_T3],
    fourth: Awaitable[_T4],
    /,
) -> tuple[_T1, _T2, _T3, _T4]: ...
@overload
async def at_once(
    first: Awaitable[_T1],
    second: Awaitable[_T2],
    third: Awaitable[_T3],
    fourth: Awaitable[_T4],
    fifth: Awaitable[_T5],
    /,
) -> tuple[_T1, _T2, _T3, _T4, _T5]: ...
@overload
async def at_once(
    first: Awaitable[_T1],
    second: Awaitable[_T2],
    third: Awaitable[_T3],
    fourth: Awaitable[_T4],
    fifth: Awaitable[_T5],
    sixth: Awaitable[_T6],
    /,
) -> tuple[_T1, _T2, _T3, _T4, _T5, _T6]: ...
@overload
async def at_once(*requests: Awaitable[Any]) -> tuple[Any, ...]: ...


async def at_once(*requests: Awaitable[Any]) -> tuple[Any, ...]:
    """Run ``requests`` at the same time; return their results in the order given.

    Each request is what a call such as ``battery_sensor.get_voltage()`` returns, not yet
    awaited (any awaitable will do). Each runs as its own task, so requests to different
    boards are on their wires at once.

    If a request raises, the others still running are cancelled, and once every one has
    stopped, that first exception is raised (any other request that failed on its own
    before it could be cancelled is named in a note on it). If the caller is cancelled,
    every request still running is cancelled and waited for first; an exception a
    request raised on its own is raised rather than the cancellation, so that it is not
    lost.

    :raises TypeError: an argument is not something to await (for instance the method
        ``get_voltage`` itself rather than ``get_voltage()``, or the value of a request
        already awaited); then no request is started.
    """
    if not requests:
        return ()
    _check_requests(requests)
    return await _Gathering(requests).results()


def _check_requests(requests: tuple[object, ...]) -> None:
    """Raise TypeError for the first argument that cannot be awaited, closing the rest."""
    for position, request in enumerate(requests, start=1):
        if type(request) is CoroutineType or inspect.isawaitable(request):
            continue
        for other in requests:
            if type(other) is CoroutineType:
                other.close()  # never started: nothing was sent, and no warning follows
        raise TypeError(_not_a_request(position, request))


def _not_a_request(position: int, request: object) -> str:
    name = getattr(request, "__name__", None)
    if callable(request) and isinstance(name, str):
        return (
            f"at_once() takes requests to make, such as motor.set_power(0.5); argument "
            f"{position} is {name} itself, not a request: call it ({name}(...)) and pass "
            f"what the call returns, without awaiting it"
        )
    hint = (
        " (at_once is for async code; with j5aio.sync each call has already been made and "
        "answered by the time it returns)"
        if request is None
        else ""
    )
    return (
        f"at_once() takes requests to make, such as battery_sensor.get_voltage(); argument "
        f"{position} is {type(request).__name__} {request!r}, which cannot be awaited: "
        f"pass the call itself, not awaited (at_once awaits it){hint}"
    )


class _Gathering:
    """The tasks of one :func:`at_once` call and what became of them.

    Each request runs in a task of its own, inside an anyio cancel scope of its own:
    ``at_once`` stops a request by cancelling its scope, never with ``Task.cancel()``,
    which would break through the ``anyio.CancelScope(shield=True)`` a request's
    clean-up may be running in.
    """

    __slots__ = ("_failures", "_remaining", "_scopes", "_stopping", "_tasks", "_waiter")

    def __init__(self, requests: tuple[Awaitable[Any], ...]) -> None:
        loop = asyncio.get_running_loop()
        self._failures: list[BaseException] = []
        self._remaining = len(requests)
        self._stopping = False
        self._waiter: asyncio.Future[None] | None = None
        self._scopes = [anyio.CancelScope() for _ in requests]
        self._tasks: list[asyncio.Task[Any]] = []
        done = self._one_done
        for request, scope in zip(requests, self._scopes, strict=True):
            task = loop.create_task(self._run(request, scope))
            task.add_done_callback(done)
            self._tasks.append(task)

    async def _run(self, request: Awaitable[Any], scope: anyio.CancelScope) -> Any:
        if self._stopping:  # stopped before its turn came: it never starts, nothing is sent
            if type(request) is CoroutineType:
                request.close()
            return None
        with scope:
            try:
                return await request
            except BaseException:
                # Stop the others now, not when the loop next runs this task's callbacks:
                # a request whose turn has not come yet then never starts.
                self._stop_all()
                raise
        return None  # (its scope was cancelled: at_once is stopping it)

    async def results(self) -> tuple[Any, ...]:
        """Wait until every task has ended; their results, or the first failure raised."""
        cancelled: asyncio.CancelledError | None = None
        while self._remaining:
            self._waiter = waiter = asyncio.get_running_loop().create_future()
            try:
                await waiter
            except asyncio.CancelledError as cancellation:
                # The caller is cancelled (perhaps again, as a cancel scope repeats it):
                # stop every request, and wait until each has really stopped.
                cancelled = cancelled or cancellation
                self._stop_all()
        if self._failures:
            raise self._first_failure()
        if cancelled is not None:
            raise cancelled
        return tuple(task.result() for task in self._tasks)

    def _one_done(self, task: asyncio.Task[Any]) -> None:
        self._remaining -= 1
        if not task.cancelled():
            failure = task.exception()  # (read here, it is never reported as unread)
            if failure is not None:
                self._failures.append(failure)
                self._stop_all()
        waiter = self._waiter
        if not self._remaining and waiter is not None and not waiter.done():
            waiter.set_result(None)

    def _stop_all(self) -> None:
        if not self._stopping:
            self._stopping = True
            for scope in self._scopes:
                scope.cancel()  # (the scope of a finished request ignores it)

    def _first_failure(self) -> BaseException:
        first, *others = self._failures
        if others:
            named = ", ".join(f"{type(other).__name__}: {other}" for other in others)
            first.add_note(f"at_once(): other requests failed at the same time: {named}")
        return first
