from __future__ import annotations

import base64
import json
import logging
import threading

import anyio
import pytest

from j5aio.service.frames import FramePublisher, encode_frame
from tests.service.helpers import eventually, longer_than

JPEG = b"\xff\xd8\xff\xe0 a tiny jpeg \xff\xd9"


def test_encode_bytes_as_the_peers_wrap_them(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("run_uuid", raising=False)
    message = json.loads(encode_frame(JPEG, timestamp=12.5))
    assert set(message) == {"timestamp", "data"}
    assert message["timestamp"] == 12.5
    prefix = "data:image/jpeg;base64, "
    assert message["data"].startswith(prefix)
    assert base64.b64decode(message["data"][len(prefix):]) == JPEG


def test_sbots_run_id_is_added(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("run_uuid", "1234-abcd")
    assert json.loads(encode_frame(JPEG))["run_uuid"] == "1234-abcd"


def test_encode_picture_with_opencv() -> None:
    np = pytest.importorskip("numpy")
    cv2 = pytest.importorskip("cv2")
    picture = np.zeros((48, 64, 3), dtype=np.uint8)
    picture[10:20, 10:30] = (0, 255, 0)
    data = json.loads(encode_frame(picture))["data"]
    jpeg = base64.b64decode(data.split(", ", 1)[1])
    decoded = cv2.imdecode(np.frombuffer(jpeg, dtype=np.uint8), cv2.IMREAD_COLOR)
    assert decoded.shape == picture.shape
    assert decoded[15, 20, 1] > 200  # the green patch survives


def test_encode_failure_is_a_value_error() -> None:
    np = pytest.importorskip("numpy")
    pytest.importorskip("cv2")
    with pytest.raises(ValueError, match="could not encode"):
        encode_frame(np.zeros((0, 0, 3), dtype=np.uint8))


@pytest.mark.parametrize("rate", [0, -1, float("nan"), float("inf"), True, "5"])
def test_bad_rate(rate: object) -> None:
    with pytest.raises(ValueError, match="frames a second"):
        FramePublisher(rate)  # type: ignore[arg-type]


def test_nothing_is_taken_before_it_runs() -> None:
    publisher = FramePublisher()
    assert not publisher.offer(JPEG)
    assert publisher.dropped == 1


async def test_a_slow_broker_drops_frames_instead_of_queueing() -> None:
    publisher = FramePublisher(max_rate=1000.0)
    release = anyio.Event()
    sent: list[bytes] = []

    async def slow_send(message: bytes) -> None:
        await release.wait()
        sent.append(message)

    async with anyio.create_task_group() as group:
        group.start_soon(publisher.run, slow_send)
        await eventually(lambda: publisher.offer(JPEG))
        await anyio.sleep(0.05)
        # the first is still being sent: every other offer is dropped, from any thread
        results: list[bool] = []
        worker = threading.Thread(target=lambda: results.extend(
            publisher.offer(JPEG) for _ in range(20)
        ))
        worker.start()
        worker.join()
        assert results == [False] * 20
        release.set()
        await eventually(lambda: len(sent) == 1)
        await eventually(lambda: publisher.offer(JPEG))  # free again
        await eventually(lambda: len(sent) == 2)
        group.cancel_scope.cancel()
    assert publisher.sent == 2 and publisher.dropped >= 20
    assert not publisher.offer(JPEG)  # stopped: nothing is taken


async def test_send_and_encode_failures_are_logged_once(caplog: pytest.LogCaptureFixture) -> None:
    publisher = FramePublisher(max_rate=1000.0)
    attempts: list[int] = []

    async def broken_send(message: bytes) -> None:
        attempts.append(1)
        raise ConnectionError("the broker is not connected")

    with caplog.at_level(logging.DEBUG, "j5aio.service"):
        async with anyio.create_task_group() as group:
            group.start_soon(publisher.run, broken_send)
            for _ in range(3):
                before = len(attempts)
                await eventually(lambda: publisher.offer(JPEG))
                await eventually(longer_than(attempts, before))
            await eventually(lambda: publisher.offer("not a picture"))  # type: ignore[arg-type]
            await eventually(lambda: publisher.dropped >= 4)
            await eventually(lambda: publisher.offer("still not"))  # type: ignore[arg-type]
            await eventually(lambda: publisher.dropped >= 5)
            group.cancel_scope.cancel()
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert len(warnings) == 2, warnings
    assert "not reaching the broker" in warnings[0]
    assert "dropped" in warnings[1]
    assert publisher.sent == 0


async def test_offer_after_the_loop_closed_is_dropped() -> None:
    publisher = FramePublisher(max_rate=1000.0)

    def closed() -> None:
        raise RuntimeError("Event loop is closed")

    publisher._wake = closed
    assert not publisher.offer(JPEG)
    publisher._wake = None
    assert publisher.dropped == 1


async def test_a_frame_made_on_demand_is_made_only_when_taken() -> None:
    publisher = FramePublisher(max_rate=0.001)  # one frame, then none for a long while
    made: list[str] = []
    sent: list[bytes] = []

    def make() -> bytes:
        made.append(threading.current_thread().name)
        return JPEG

    async def send(message: bytes) -> None:
        sent.append(message)

    async with anyio.create_task_group() as group:
        group.start_soon(publisher.run, send)
        await eventually(lambda: publisher.offer(make))
        for _ in range(10):
            assert not publisher.offer(make)  # too soon: never made
        await eventually(lambda: len(sent) == 1)
        group.cancel_scope.cancel()
    assert len(made) == 1 and made[0] != threading.current_thread().name
    assert json.loads(sent[0])["data"].endswith(base64.b64encode(JPEG).decode())
