"""sbot's ``vision``: the robot's camera, finding markers with their distances and angles."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

from ._errors import translate_errors
from ._kit import KitLink
from .game_specific import MARKER_SIZES
from .marker import Marker

if TYPE_CHECKING:
    from j5aio.sync import MarkerCamera
    from j5aio.vision.sizes import MarkerSizes

__all__ = ["PathLike", "Vision"]

PathLike = Union[Path, str]  # noqa: UP007 - sbot's alias

#: The size detection gives a marker the game has none for: such markers are dropped.
_UNKNOWN_SIZE = 1.0


def _game_sizes() -> MarkerSizes:
    from j5aio.vision.sizes import MarkerSizes

    table = {
        marker_id: float(size) for ids, size in MARKER_SIZES.items() for marker_id in ids
    }
    return MarkerSizes(table, default=_UNKNOWN_SIZE)


def _jpeg_path(save: PathLike) -> Path:
    path = Path(save)
    return path if path.suffix else path.with_suffix(".jpg")


@translate_errors
class Vision:
    """The robot's camera: find markers (as sbot's ``Marker``) and take pictures.

    Markers whose ids are not in the game's table of sizes are left out, as sbot does.

    :param boards: the kit the camera is found on.
    """

    __slots__ = ("_boards", "_sizes")

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards
        self._sizes: MarkerSizes | None = None

    def _camera(self) -> MarkerCamera:
        camera = self._boards.robot.camera
        if camera is None:
            raise ValueError("No cameras connected")
        return camera

    def detect_markers(
        self, *, frame: Any | None = None, save: PathLike | None = None,
    ) -> list[Marker]:
        """Find the markers in a picture, nearest first.

        :param frame: a picture to look in (a BGR numpy array) instead of taking one.
        :param save: write the picture, with the markers outlined, to this path (given
            the JPEG suffix if it has none).
        :raises ValueError: there is no camera.
        """
        from j5aio.vision.detect import detect_markers

        camera = self._camera()
        if self._sizes is None:
            self._sizes = _game_sizes()
        if frame is None:
            frame = camera.capture()
        found = [
            marker
            for marker in detect_markers(frame, camera.calibration, self._sizes)
            if marker.size != _UNKNOWN_SIZE
        ]
        if save:
            from j5aio.vision.annotate import annotate, write_image

            write_image(_jpeg_path(save), annotate(frame, found))
        return [Marker.from_core(marker) for marker in found]

    def capture(self, save: PathLike | None = None) -> Any:
        """Take a picture and return it (a BGR numpy array).

        :param save: also write it, as taken, to this path (given the JPEG suffix if it
            has none).
        :raises ValueError: there is no camera.
        """
        frame = self._camera().capture()
        if save:
            from j5aio.vision.annotate import write_image

            write_image(_jpeg_path(save), frame)
        return frame
