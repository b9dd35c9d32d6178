"""FileCameraBackend: a camera whose pictures are image files or numpy arrays.

For tests, and for replaying a recorded run::

    board = FileCameraBackend.make_board(["run/001.png", "run/002.png"], calibration=cal)
    markers = await board.camera.see()      # the markers in run/001.png

Each picture taken is the next one in the list; the last one is repeated once they run
out (``loop=True`` starts again from the first instead).
"""

from __future__ import annotations

import threading
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.boards.camera import CameraBoard
from j5aio.errors import CommunicationError
from j5aio.vision._optional import require
from j5aio.vision.sizes import MarkerSizes

if TYPE_CHECKING:
    from j5aio.boards.board import Board
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image

__all__ = ["FileCameraBackend"]


class FileCameraBackend(FrameCameraBackend):
    """A camera that "takes" pictures from files or arrays, in order.

    :param frames: image file paths or numpy arrays (BGR or greyscale); at least one.
    :param calibration: the calibration of the camera that took them, if known.
    :param name: the camera's name.
    :param loop: start again at the first picture after the last (default: repeat the last).
    :param marker_sizes: the table the camera starts with.
    :raises TypeError: a frame is neither a path nor an array.
    :raises ValueError: there are no frames.
    """

    def __init__(
        self,
        frames: Sequence[str | Path | Image],
        calibration: CameraCalibration | None = None,
        *,
        name: str = "files",
        loop: bool = False,
        marker_sizes: Mapping[int, float] | None = None,
    ) -> None:
        if isinstance(frames, str | Path) or not isinstance(frames, Sequence):
            raise TypeError("frames must be a list of image paths or numpy arrays")
        if not frames:
            raise ValueError("a file camera needs at least one picture")
        np = require("numpy")
        for frame in frames:
            if not isinstance(frame, str | Path | np.ndarray):
                raise TypeError(
                    f"each frame must be an image path or a numpy array, not {type(frame).__name__}"
                )
        super().__init__(name, calibration)
        self._frames: list[Any] = list(frames)
        self._loop = loop
        self._next = 0
        self._lock = threading.Lock()
        self.marker_sizes = None if marker_sizes is None else MarkerSizes(marker_sizes)

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        """Find nothing: a file camera is made by hand (see :meth:`make_board`)."""
        return []

    @classmethod
    def make_board(
        cls,
        frames: Sequence[str | Path | Image],
        calibration: CameraCalibration | None = None,
        **options: Any,
    ) -> CameraBoard:
        """Return a camera board whose pictures are ``frames`` (options as the constructor)."""
        backend = cls(frames, calibration, **options)
        return CameraBoard(backend.name, backend)

    def grab(self) -> Image:
        """Return the next picture.

        :raises CommunicationError: an image file could not be read.
        """
        with self._lock:
            frame = self._frames[self._next]
            if self._next + 1 < len(self._frames):
                self._next += 1
            elif self._loop:
                self._next = 0
        if isinstance(frame, str | Path):
            image = require("cv2").imread(str(frame), 1)
            if image is None:
                raise CommunicationError(f"camera {self.name}: could not read the image {frame}")
            return image  # type: ignore[no-any-return]
        return frame  # type: ignore[no-any-return]
