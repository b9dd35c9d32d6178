"""Camera frames for the robot's web page: encoded off the event loop, never queued.

The robot's web page (astoria's) shows the frames the program's camera annotates, as
sr-robot3 and sbot send them through april_vision: a JPEG, base64-encoded, after
``data:image/jpeg;base64, ``, wrapped as JSON ``{"timestamp": <Unix time>, "data": ...}``
and published with QoS 1 on ``camera/annotated`` (under sbot's prefix when the service
is configured by a URL). As sbot does, the value of the ``run_uuid`` environment variable,
where it is set, is added as ``"run_uuid"``.

:meth:`FramePublisher.offer` costs its caller no more than a clock read and a lock: at most
``max_rate`` frames a second are taken, one at a time; a frame offered while the last is
still being encoded or sent (a slow broker), or too soon after it, is dropped, never
queued. The encoding runs in a worker thread.
"""

from __future__ import annotations

import base64
import json
import logging
import math
import os
import threading
import time
from collections.abc import Awaitable, Callable
from typing import Final, TypeAlias

import anyio
import anyio.to_thread

from j5aio.service.faults import FaultLog
from j5aio.vision.image import Image  # (only a name at run time: numpy is not imported)

__all__ = [
    "DEFAULT_MAX_RATE",
    "JPEG_QUALITY",
    "RUN_ID_VARIABLE",
    "FrameLike",
    "FramePublisher",
    "encode_frame",
]

LOGGER = logging.getLogger(__name__)

#: Frames a second sent at most, unless told otherwise.
DEFAULT_MAX_RATE: Final = 5.0
#: The JPEG quality used (as april_vision's sender).
JPEG_QUALITY: Final = 80
#: The environment variable whose value sbot adds to each frame as ``run_uuid``.
RUN_ID_VARIABLE: Final = "run_uuid"
_DATA_URL_PREFIX: Final = b"data:image/jpeg;base64, "
_SEND_TIMEOUT: Final = 2.0

#: Sends one encoded payload; raises on failure.
Sender = Callable[[bytes], Awaitable[None]]
#: What can be offered: a picture, a JPEG's bytes, or a call that makes either (called
#: only for a frame that is taken, on the encoding thread: e.g. the annotation).
FrameLike: TypeAlias = Image | bytes | Callable[[], Image | bytes]


def encode_frame(frame: Image | bytes, timestamp: float | None = None) -> bytes:
    """The message for one frame: JSON ``{"timestamp", "data"}`` with the JPEG in base64.

    :param frame: a picture (a numpy array, BGR or greyscale: encoded as JPEG with
        OpenCV) or the bytes of a JPEG.
    :param timestamp: the Unix time to give; now if omitted.
    :raises ~j5aio.vision.VisionNotInstalledError: a picture was given and OpenCV is not
        installed.
    :raises ValueError: OpenCV could not encode the picture.
    """
    if isinstance(frame, bytes | bytearray | memoryview):
        jpeg = bytes(frame)
    else:
        from j5aio.vision._optional import require

        cv2 = require("cv2")
        try:
            ok, buffer = cv2.imencode(".jpg", frame, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])
        except (cv2.error, TypeError) as exc:
            raise ValueError(f"OpenCV could not encode the frame as JPEG: {exc}") from None
        if not ok:  # pragma: no cover - OpenCV raises rather than saying so
            raise ValueError("OpenCV could not encode the frame as JPEG")
        jpeg = buffer.tobytes()
    data = (_DATA_URL_PREFIX + base64.b64encode(jpeg)).decode("ascii")
    when = time.time() if timestamp is None else timestamp
    message: dict[str, object] = {"timestamp": when, "data": data}
    run = os.environ.get(RUN_ID_VARIABLE)
    if run is not None:  # sbot's runner names its runs so
        message["run_uuid"] = run
    return json.dumps(message).encode("ascii")


def _make_and_encode(frame: FrameLike) -> bytes:
    if callable(frame):
        frame = frame()
    return encode_frame(frame)


class FramePublisher:
    """Takes frames from any thread and sends them, rate-limited, one at a time.

    :param max_rate: frames a second at most (more than 0).
    :raises ValueError: ``max_rate`` is not a positive number.
    """

    def __init__(self, max_rate: float = DEFAULT_MAX_RATE) -> None:
        if (
            isinstance(max_rate, bool)
            or not isinstance(max_rate, int | float)
            or not math.isfinite(max_rate)
            or max_rate <= 0
        ):
            raise ValueError(f"max_rate must be a number of frames a second above 0, "
                             f"not {max_rate!r}")
        self._interval = 1.0 / max_rate
        self._lock = threading.Lock()
        self._busy = False
        self._last_taken = -math.inf
        self._wake: Callable[[], None] | None = None
        self._pending: FrameLike | None = None
        self._faults = FaultLog(LOGGER)
        #: How many frames were sent, and how many dropped.
        self.sent = 0
        self.dropped = 0

    def offer(self, frame: FrameLike) -> bool:
        """Hand over a frame to send; from any thread, never blocking.

        The publisher keeps a reference to ``frame`` until it is encoded: give it one
        that is not changed afterwards (a new array, such as
        :func:`~j5aio.vision.annotate.annotate` returns), or a call that makes the frame
        (it runs only if the frame is taken, on the encoding thread).

        :returns: whether the frame was taken (``False``: dropped, because the service
            is not running, the last frame is still going, or it came too soon).
        """
        now = time.monotonic()
        with self._lock:
            wake = self._wake
            if wake is None or self._busy or now - self._last_taken < self._interval:
                self.dropped += 1
                return False
            self._busy = True
            self._last_taken = now
            self._pending = frame
        try:
            wake()
        except RuntimeError:  # the service's event loop has closed
            with self._lock:
                self._busy = False
                self._pending = None
            self.dropped += 1
            return False
        return True

    async def run(self, send: Sender) -> None:
        """Send the frames offered, until cancelled. Call it in one task only.

        :param send: sends one encoded message; its failure drops the frame (logged once).
        """
        import asyncio

        loop = asyncio.get_running_loop()
        ready = asyncio.Event()

        def wake() -> None:
            loop.call_soon_threadsafe(ready.set)

        with self._lock:
            self._wake = wake
        try:
            while True:
                await ready.wait()
                ready.clear()
                with self._lock:
                    frame, self._pending = self._pending, None
                if frame is not None:
                    try:
                        await self._send(frame, send)
                    finally:
                        with self._lock:
                            self._busy = False
        finally:
            with self._lock:
                self._wake = None
                self._busy = False
                self._pending = None

    async def _send(self, frame: FrameLike, send: Sender) -> None:
        try:
            message = await anyio.to_thread.run_sync(_make_and_encode, frame)
        except Exception as exc:  # a frame that cannot be made or encoded is dropped
            self.dropped += 1
            self._faults.report("encode", "Robot service: a camera frame was dropped: %s", exc)
            return
        try:
            with anyio.fail_after(_SEND_TIMEOUT):
                await send(message)
        except Exception as exc:  # the broker is gone or slow: drop, say so once
            self.dropped += 1
            self._faults.report(
                "send", "Robot service: camera frames are not reaching the broker: %r", exc
            )
            return
        self._faults.forget("send")
        self.sent += 1
