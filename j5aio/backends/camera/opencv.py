"""OpenCVCameraBackend: a webcam (a Logitech C270 or C500, say) through OpenCV's capture.

Discovery looks at ``/dev/video*`` on Linux (cameras 0 to 3 elsewhere); a camera whose USB
id is known gets its built-in calibration at the resolution it runs at, any other none
(ids and pixels only) unless one is given. Without the vision libraries, discovery finds
no camera and says, once, what to install.
"""

from __future__ import annotations

import glob
import logging
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.boards.camera import CameraBoard
from j5aio.errors import CommunicationError
from j5aio.vision._optional import VisionNotInstalledError, require
from j5aio.vision.calibration import KNOWN_USB_IDS, known_calibration

if TYPE_CHECKING:
    from j5aio.backends.hardware.options import DiscoveryOptions
    from j5aio.boards.board import Board
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image

__all__ = ["OpenCVCameraBackend", "usb_id_of"]

LOGGER = logging.getLogger(__name__)

#: The resolution a webcam is asked for unless told otherwise.
DEFAULT_RESOLUTION = (1280, 960)


def usb_id_of(device: str, sysfs: Path = Path("/sys/class/video4linux")) -> str | None:
    """Return ``"vvvv:pppp"`` of a Linux video device, or ``None`` if it cannot be read.

    :param device: the device path, e.g. ``/dev/video0``.
    :param sysfs: where the kernel lists video devices.
    """
    name = Path(device).name
    # device/ is the USB interface; its parent is the USB device, with its ids.
    base = sysfs / name / "device" / ".."
    try:
        vendor = (base / "idVendor").read_text().strip()
        product = (base / "idProduct").read_text().strip()
    except OSError:
        return None
    return f"{vendor}:{product}"


class OpenCVCameraBackend(FrameCameraBackend):
    """A webcam read through ``cv2.VideoCapture``.

    :param device: the device path (``/dev/video0``) or index (``0``).
    :param calibration: the camera's calibration; by default the built-in one of a known
        camera at the resolution it gives, or ``None``.
    :param resolution: the ``(width, height)`` to ask the camera for.
    :raises ~j5aio.vision.VisionNotInstalledError: the vision libraries are not installed.
    :raises CommunicationError: the camera could not be opened.
    """

    def __init__(
        self,
        device: str | int,
        calibration: CameraCalibration | None = None,
        *,
        resolution: tuple[int, int] = DEFAULT_RESOLUTION,
    ) -> None:
        cv2 = require("cv2")
        super().__init__(str(device), calibration)
        self._capture: Any = cv2.VideoCapture(device)
        if not self._capture.isOpened():
            raise CommunicationError(f"camera {device}: could not be opened")
        self._capture.set(cv2.CAP_PROP_FRAME_WIDTH, resolution[0])
        self._capture.set(cv2.CAP_PROP_FRAME_HEIGHT, resolution[1])
        # Keep one frame in the driver's queue, so that a picture is fresh.
        self._capture.set(cv2.CAP_PROP_BUFFERSIZE, 1)
        width = int(self._capture.get(cv2.CAP_PROP_FRAME_WIDTH))
        height = int(self._capture.get(cv2.CAP_PROP_FRAME_HEIGHT))
        if calibration is None and isinstance(device, str):
            camera = KNOWN_USB_IDS.get(usb_id_of(device) or "")
            if camera is not None:
                try:
                    self._calibration = known_calibration(camera, width, height)
                except ValueError:
                    LOGGER.warning("%s at %dx%d has no built-in calibration", camera, width, height)
        if self._calibration is None:
            LOGGER.warning(
                "camera %s has no calibration: it finds marker ids and pixels, but distances "
                "and angles need a calibration (CameraCalibration.from_file)",
                device,
            )

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Open every camera found.

        Without the vision libraries none is opened: a camera plugged in then gets one
        warning saying what to install; with no camera plugged in nothing is said (a
        program that uses no camera should not hear about one).

        ``options`` (for serial and USB discovery) is accepted and ignored.
        """
        on_linux = sys.platform.startswith("linux")
        devices: list[str | int] = sorted(glob.glob("/dev/video*")) if on_linux else [0, 1, 2, 3]
        if not devices:
            return []
        try:
            require("cv2")
        except VisionNotInstalledError as exc:
            # Elsewhere than Linux the devices are guesses: no warning for a guess.
            LOGGER.log(logging.WARNING if on_linux else logging.DEBUG, "%s", exc)
            return []
        boards: list[Board] = []
        for device in devices:
            try:
                backend = cls(device)
            except CommunicationError:
                continue
            boards.append(CameraBoard(backend.name, backend))
        return boards

    def grab(self) -> Image:
        """Read the next frame from the camera.

        :raises CommunicationError: the camera gave no frame (unplugged, say).
        """
        ok, frame = self._capture.read()
        if not ok or frame is None:
            raise CommunicationError(f"camera {self.name}: no picture (is it still plugged in?)")
        return frame  # type: ignore[no-any-return]

    async def close(self) -> None:
        """Release the camera and stop its worker thread."""
        await self._worker_here().run(self._capture.release)
        await super().close()
