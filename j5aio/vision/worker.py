"""One worker thread per camera: capture and detection run there, off the event loop.

Jobs run in the order they were asked for. A caller cancelled while its job is still
queued takes the job off the queue; one cancelled while the job runs is released at once,
and the job's result is dropped when it finishes.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import TYPE_CHECKING, ParamSpec, TypeVar

if TYPE_CHECKING:
    from concurrent.futures import ThreadPoolExecutor

__all__ = ["CameraWorker"]

T = TypeVar("T")
P = ParamSpec("P")


class CameraWorker:
    """A single dedicated thread that runs one camera's blocking calls in order.

    The thread's pool is made by the first job: a camera that is never looked through
    (every robot on the simulated kit has one) costs no pool and no thread.

    :param name: names the thread, e.g. ``"camera /dev/video0"``.
    """

    def __init__(self, name: str) -> None:
        self._name = name
        self._executor: ThreadPoolExecutor | None = None
        self._closed = False

    @property
    def is_closed(self) -> bool:
        """Whether :meth:`close` has been called."""
        return self._closed

    async def run(self, function: Callable[P, T], *args: P.args, **kwargs: P.kwargs) -> T:
        """Run ``function(*args, **kwargs)`` on the thread and return its result.

        :raises RuntimeError: the worker is closed.
        """
        if self._closed:
            raise RuntimeError("this camera is closed")
        if self._executor is None:
            from concurrent.futures import ThreadPoolExecutor

            self._executor = ThreadPoolExecutor(
                max_workers=1, thread_name_prefix=f"j5aio {self._name}"
            )
        future = self._executor.submit(function, *args, **kwargs)
        return await asyncio.wrap_future(future)

    def close(self) -> None:
        """Stop the thread once the running job ends; queued jobs are dropped."""
        self._closed = True
        if self._executor is not None:
            self._executor.shutdown(wait=False, cancel_futures=True)
