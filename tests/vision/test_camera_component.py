"""MarkerCamera and its backends: files and arrays, the console, the worker thread."""

from __future__ import annotations

import math
import threading
import time
from pathlib import Path
from typing import Any

import anyio
import pytest

np = pytest.importorskip("numpy")
cv2 = pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

from j5aio.backends.camera import FileCameraBackend  # noqa: E402
from j5aio.backends.console.camera import CameraConsoleBackend, parse_markers  # noqa: E402
from j5aio.boards.camera import CameraBoard  # noqa: E402
from j5aio.components.marker_camera import MarkerCamera  # noqa: E402
from j5aio.errors import CommunicationError, NotSupportedByHardwareError  # noqa: E402
from j5aio.simulator.camera import DEFAULT_CALIBRATION  # noqa: E402
from j5aio.testing.console import ConsoleScript  # noqa: E402
from j5aio.vision import MarkerSizes, Orientation, UnknownMarkerError  # noqa: E402
from j5aio.vision.geometry import rotation_from_orientation  # noqa: E402
from j5aio.vision.render import MarkerItem, render  # noqa: E402
from j5aio.vision.worker import CameraWorker  # noqa: E402


def picture(*ids_and_distances: tuple[int, float]) -> Any:
    items = [
        MarkerItem(marker_id, 150, (-300.0 + 500 * k, 0.0, distance),
                   rotation_from_orientation(Orientation(0, 0, 0)))
        for k, (marker_id, distance) in enumerate(ids_and_distances)
    ]
    return render(DEFAULT_CALIBRATION, (1280, 720), items)


async def test_a_file_camera_sees_its_pictures_in_order(tmp_path: Path) -> None:
    first = tmp_path / "first.png"
    cv2.imwrite(str(first), picture((4, 1500)))
    board = FileCameraBackend.make_board(
        [first, picture((5, 2000), (6, 1200))], DEFAULT_CALIBRATION,
        marker_sizes={4: 150, 5: 150, 6: 150},
    )
    try:
        camera = board.camera
        assert camera.marker_sizes.size_of(5) == 150
        assert await camera.get_calibration() is DEFAULT_CALIBRATION
        (marker,) = await camera.see()
        assert marker.id == 4
        assert marker.position.distance == pytest.approx(math.hypot(300, 1500), rel=0.01)
        markers = await camera.see()
        assert [m.id for m in markers] == [6, 5]  # nearest first
        assert await camera.see_ids() == [5, 6]  # the last picture repeats
        frame = await camera.capture()
        assert frame.shape == (720, 1280, 3)
        out = tmp_path / "seen.png"
        await camera.save(out)
        annotated = cv2.imread(str(out))
        assert annotated.shape == (720, 1280, 3)
        assert not np.array_equal(annotated, frame)  # the outlines are drawn
        assert await board.camera.see_ids() == [5, 6]
    finally:
        await board.close()


async def test_a_looping_file_camera_starts_again_and_a_missing_file_is_an_error(
    tmp_path: Path,
) -> None:
    board = FileCameraBackend.make_board(
        [picture((1, 1000)), tmp_path / "missing.png"], loop=True, name="replay"
    )
    try:
        assert board.serial_number == "replay"
        assert await board.camera.see_ids() == [1]
        with pytest.raises(CommunicationError, match="could not read the image"):
            await board.camera.see_ids()
        assert await board.camera.see_ids() == [1]
    finally:
        await board.close()
    assert await FileCameraBackend.discover() == []


def test_file_camera_checks_its_frames() -> None:
    with pytest.raises(ValueError, match="at least one"):
        FileCameraBackend([])
    with pytest.raises(TypeError, match="list of image paths"):
        FileCameraBackend("one.png")
    with pytest.raises(TypeError, match="image path or a numpy array"):
        FileCameraBackend([3])  # type: ignore[list-item]


async def test_uncalibrated_camera_gives_ids_and_pixels() -> None:
    board = FileCameraBackend.make_board([picture((8, 1000))])
    try:
        board.camera.set_marker_sizes({8: 150})
        (marker,) = await board.camera.see()
        assert marker.id == 8 and not marker.has_pose
        assert await board.camera.get_calibration() is None
    finally:
        await board.close()


async def test_marker_sizes_are_checked_and_unknown_ids_are_errors() -> None:
    board = FileCameraBackend.make_board([picture((8, 1000))])
    camera = board.camera
    try:
        with pytest.raises(UnknownMarkerError, match="marker 8"):
            await camera.see()
        with pytest.raises(TypeError, match="dict of marker ids"):
            camera.set_marker_sizes([150])  # type: ignore[arg-type]
        with pytest.raises(ValueError, match="more than 0"):
            camera.set_marker_sizes({8: -1})
        table = MarkerSizes({8: 100})
        camera.set_marker_sizes(table)
        assert camera.marker_sizes is table
        (marker,) = await camera.see()
        assert marker.size == 100
    finally:
        await board.close()


async def test_save_checks_the_path_before_taking_a_picture(tmp_path: Path) -> None:
    board = FileCameraBackend.make_board([tmp_path / "never-read.png"])
    try:
        with pytest.raises(TypeError, match="str or a Path"):
            await board.camera.save(3)  # type: ignore[arg-type]
        with pytest.raises(ValueError, match="image format"):
            await board.camera.save(tmp_path / "out.txt")
        with pytest.raises(OSError, match="could not write"):
            backend = board.backend
            assert isinstance(backend, FileCameraBackend)
            from j5aio.vision.annotate import write_image

            write_image(tmp_path / "no-such-dir" / "x.png", picture())
    finally:
        await board.close()


def test_camera_board_has_one_marker_camera() -> None:
    assert CameraBoard.supported_components() == {MarkerCamera}
    assert MarkerCamera.interface_class().__name__ == "MarkerCameraInterface"


async def test_the_camera_runs_on_its_own_thread_and_never_blocks_the_loop() -> None:
    threads: list[str] = []

    class SlowFiles(FileCameraBackend):
        def grab(self) -> Any:
            threads.append(threading.current_thread().name)
            time.sleep(0.2)
            return super().grab()

    backend = SlowFiles([picture((2, 1000))])
    board = CameraBoard("slow", backend)
    ticks = 0

    async def tick() -> None:
        nonlocal ticks
        while True:
            await anyio.sleep(0.01)
            ticks += 1

    try:
        async with anyio.create_task_group() as group:
            group.start_soon(tick)
            assert await board.camera.see_ids() == [2]
            group.cancel_scope.cancel()
        assert ticks >= 5  # the loop ran while the camera worked
        assert threads == ["j5aio camera files_0"]
    finally:
        await board.close()


async def test_a_cancelled_queued_job_never_runs_and_a_closed_worker_refuses() -> None:
    worker = CameraWorker("test")
    started = threading.Event()
    release = threading.Event()
    ran: list[str] = []

    def slow() -> str:
        started.set()
        release.wait(5)
        ran.append("slow")
        return "slow"

    def queued() -> None:
        ran.append("queued")

    async with anyio.create_task_group() as group:
        group.start_soon(worker.run, slow)
        await anyio.to_thread.run_sync(started.wait)
        with anyio.move_on_after(0.05):
            await worker.run(queued)
        release.set()
    assert ran == ["slow"]
    assert not worker.is_closed
    worker.close()
    assert worker.is_closed
    with pytest.raises(RuntimeError, match="closed"):
        await worker.run(queued)


# -- console --------------------------------------------------------------------------


async def test_console_camera_asks_which_markers_are_seen() -> None:
    script = ConsoleScript()
    backend = CameraConsoleBackend("SERIAL", console_class=script.console_class())
    board = CameraBoard("SERIAL", backend)
    camera = board.camera
    camera.set_marker_sizes({3: 150, 7: 200})
    script.answer("Markers seen", "7 2200 -4 2, 3 1500 10")
    markers = await camera.see()
    assert [m.id for m in markers] == [3, 7]
    near = markers[0]
    assert near.position.distance == pytest.approx(1500)
    assert math.degrees(near.position.horizontal_angle) == pytest.approx(10)
    assert near.cartesian.y < 0  # to the right is negative y
    assert math.degrees(markers[1].position.vertical_angle) == pytest.approx(2)
    assert markers[1].size == 200
    assert script.prompts == [
        "CameraBoard(SERIAL): Markers seen (id distance_mm bearing_deg, ...): "
    ]
    script.answer("Markers seen", "")
    assert await camera.see() == []
    script.answer("Marker ids seen", "7, 3")
    assert await camera.see_ids() == [3, 7]
    script.answer("Markers seen", "9 1000 0")
    with pytest.raises(UnknownMarkerError):
        await camera.see()
    with pytest.raises(NotSupportedByHardwareError, match="no pictures"):
        await camera.capture()
    with pytest.raises(NotSupportedByHardwareError, match="no pictures"):
        await camera.save("x.png")
    assert await camera.get_calibration() is None


async def test_console_camera_asks_again_after_a_bad_answer() -> None:
    script = ConsoleScript()
    backend = CameraConsoleBackend("SERIAL", console_class=script.console_class())
    camera = CameraBoard("SERIAL", backend).camera
    camera.set_marker_sizes(MarkerSizes(default=150))
    script.answer("Markers seen", "3 1500")
    script.answer("Markers seen", "3 1500 0")
    assert [m.id for m in await camera.see()] == [3]
    assert any("Unable to construct" in line for line in script.printed)
    script.answer("Marker ids seen", "999")
    script.answer("Marker ids seen", "1")
    assert await camera.see_ids() == [1]


@pytest.mark.parametrize(
    ("answer", "message"),
    [("3 1500", "give 'id"), ("600 100 0", "not an AprilTag"), ("3 -1 0", "more than 0")],
)
def test_console_marker_answers_are_checked(answer: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        parse_markers(answer)
