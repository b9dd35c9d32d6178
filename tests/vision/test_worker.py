"""Tests of CameraWorker: one thread a camera, started by its first job."""

from __future__ import annotations

import threading

import pytest

from j5aio.vision.worker import CameraWorker


def _worker_threads(name: str) -> list[str]:
    return [thread.name for thread in threading.enumerate() if thread.name.startswith(name)]


async def test_a_worker_starts_its_thread_with_its_first_job() -> None:
    worker = CameraWorker("lazy one")
    try:
        assert _worker_threads("j5aio lazy one") == []  # made, never used: no thread
        assert await worker.run(lambda: threading.current_thread().name) == "j5aio lazy one_0"
        assert await worker.run(lambda: 6 * 7) == 42  # the same thread, in order
        assert _worker_threads("j5aio lazy one") == ["j5aio lazy one_0"]
    finally:
        worker.close()


async def test_a_worker_closed_before_any_job_refuses_one() -> None:
    worker = CameraWorker("never used")
    worker.close()
    worker.close()  # (closing twice is harmless)
    assert worker.is_closed
    with pytest.raises(RuntimeError, match="closed"):
        await worker.run(lambda: None)
    assert _worker_threads("j5aio never used") == []
