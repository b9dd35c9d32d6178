"""The webcam backend, with OpenCV's capture replaced by a stand-in camera."""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

import pytest

np = pytest.importorskip("numpy")
cv2 = pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

import j5aio.backends.camera.opencv as opencv_backend  # noqa: E402
from j5aio.backends.camera import OpenCVCameraBackend  # noqa: E402
from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT  # noqa: E402
from j5aio.boards.camera import CameraBoard  # noqa: E402
from j5aio.errors import CommunicationError  # noqa: E402
from j5aio.simulator.camera import DEFAULT_CALIBRATION  # noqa: E402
from j5aio.vision import KNOWN_CALIBRATIONS, Orientation  # noqa: E402
from j5aio.vision.geometry import rotation_from_orientation  # noqa: E402
from j5aio.vision.render import MarkerItem, render  # noqa: E402


class FakeCapture:
    """Stands in for cv2.VideoCapture: a camera giving one rendered picture."""

    opened: dict[object, FakeCapture] = {}

    def __init__(self, device: object) -> None:
        self.device = device
        self.props: dict[int, float] = {}
        self.released = False
        self.working = device != "/dev/video9"
        self.frames_left = 3
        FakeCapture.opened[device] = self

    def isOpened(self) -> bool:  # noqa: N802 - OpenCV's name
        return self.working

    def set(self, prop: int, value: float) -> bool:
        self.props[prop] = value
        return True

    def get(self, prop: int) -> float:
        return self.props.get(prop, 0.0)

    def read(self) -> tuple[bool, Any]:
        if self.frames_left == 0:
            return False, None
        self.frames_left -= 1
        width = int(self.props[cv2.CAP_PROP_FRAME_WIDTH])
        height = int(self.props[cv2.CAP_PROP_FRAME_HEIGHT])
        calibration = DEFAULT_CALIBRATION.scaled_to(1280, 720)
        upright = rotation_from_orientation(Orientation(0, 0, 0))
        item = MarkerItem(3, 150, (0.0, 0.0, 1000.0), upright)
        frame = render(calibration, (1280, 720), [item])
        return True, cv2.resize(frame, (width, height))

    def release(self) -> None:
        self.released = True


@pytest.fixture
def fake_cv2(monkeypatch: pytest.MonkeyPatch) -> None:
    FakeCapture.opened = {}
    monkeypatch.setattr(cv2, "VideoCapture", FakeCapture)


def test_the_hardware_environment_has_webcams() -> None:
    assert HARDWARE_ENVIRONMENT.get_backend(CameraBoard) is OpenCVCameraBackend


async def test_discovery_opens_each_video_device_and_knows_a_c270(
    fake_cv2: None, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr("sys.platform", "linux")
    monkeypatch.setattr(
        "glob.glob", lambda pattern: ["/dev/video2", "/dev/video0", "/dev/video9"]
    )
    ids = {"/dev/video0": "046d:0825", "/dev/video2": "1234:5678"}
    monkeypatch.setattr(opencv_backend, "usb_id_of", lambda device: ids.get(device))
    caplog.set_level(logging.WARNING)
    boards = await OpenCVCameraBackend.discover()
    try:
        assert [b.serial_number for b in boards] == ["/dev/video0", "/dev/video2"]
        c270 = await boards[0].camera.get_calibration()  # type: ignore[attr-defined]
        assert c270 == KNOWN_CALIBRATIONS["Logitech C270"]
        assert await boards[1].camera.get_calibration() is None  # type: ignore[attr-defined]
        assert "/dev/video2 has no calibration" in caplog.text
        camera = boards[0].camera  # type: ignore[attr-defined]
        camera.set_marker_sizes({3: 150})
        (marker,) = await camera.see()
        assert marker.id == 3 and marker.has_pose
        assert await camera.see_ids() == [3]
        await camera.see_ids()
        with pytest.raises(CommunicationError, match="no picture"):
            await camera.see_ids()
    finally:
        for board in boards:
            await board.close()
    assert FakeCapture.opened["/dev/video0"].released


async def test_a_known_camera_at_an_unknown_shape_and_other_platforms(
    fake_cv2: None, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(opencv_backend, "usb_id_of", lambda device: "046d:0825")
    caplog.set_level(logging.WARNING)
    backend = OpenCVCameraBackend("/dev/video0", resolution=(1280, 720))
    try:
        assert await backend.get_calibration(0) is None
        assert "Logitech C270 at 1280x720 has no built-in calibration" in caplog.text
    finally:
        await backend.close()
    given = OpenCVCameraBackend(1, DEFAULT_CALIBRATION)
    try:
        assert await given.get_calibration(0) is DEFAULT_CALIBRATION
        assert given.firmware_version is None
    finally:
        await given.close()
    monkeypatch.setattr("sys.platform", "win32")
    boards = await OpenCVCameraBackend.discover()
    try:
        assert [b.serial_number for b in boards] == ["0", "1", "2", "3"]
    finally:
        for board in boards:
            await board.close()


def test_usb_ids_come_from_sysfs_or_are_unknown(tmp_path: Path) -> None:
    assert opencv_backend.usb_id_of("/dev/video-that-is-not-there") is None
    usb_device = tmp_path / "usb1" / "1-2"
    (usb_device / "1-2:1.0").mkdir(parents=True)
    (usb_device / "idVendor").write_text("046d\n")
    (usb_device / "idProduct").write_text("0825\n")
    (tmp_path / "video4linux" / "video0").mkdir(parents=True)
    (tmp_path / "video4linux" / "video0" / "device").symlink_to(usb_device / "1-2:1.0")
    sysfs = tmp_path / "video4linux"
    assert opencv_backend.usb_id_of("/dev/video0", sysfs) == "046d:0825"
    assert opencv_backend.usb_id_of("/dev/video1", sysfs) is None
