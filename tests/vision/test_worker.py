"""Tests of CameraWorker: one thread a camera, started by its first job."""

from __future__ import annotations

import threading
from typing import Any

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


async def test_a_camera_makes_its_worker_at_its_first_look_and_refuses_once_closed() -> None:
    from j5aio.backends.camera.frames import FrameCameraBackend

    class StillCamera(FrameCameraBackend):
        @classmethod
        async def discover(cls) -> list[Any]:
            return []

        def grab(self) -> Any:
            return "a picture"

    never = StillCamera("still never")
    assert never._worker is None  # made, never looked through: no worker
    await never.close()
    assert never._worker is None
    with pytest.raises(RuntimeError, match="this camera is closed"):
        await never.capture_frame(0)
    used = StillCamera("still used")
    assert await used.capture_frame(0) == "a picture"
    assert used._worker is not None
    assert _worker_threads("j5aio camera still used") == ["j5aio camera still used_0"]
    await used.close()
    assert used._worker.is_closed
    with pytest.raises(RuntimeError, match="this camera is closed"):
        await used.capture_frame(0)
