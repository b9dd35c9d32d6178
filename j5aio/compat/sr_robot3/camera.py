"""sr-robot3's camera on j5aio's marker camera: ``see`` and ``capture``, with ``save``."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.compat.sr_robot3.game_specific import marker_size_table
from j5aio.compat.sr_robot3.marker import Marker
from j5aio.compat.sr_robot3.utils import BoardIdentity
from j5aio.errors import CommunicationError

if TYPE_CHECKING:
    from j5aio.sync import MarkerCamera
    from j5aio.vision.markers import Marker as CoreMarker

__all__ = ["AprilCamera", "PathLike"]

PathLike = Path | str


def _jpeg(path: PathLike) -> Path:
    """``path``, given a ``.jpg`` suffix if it has none (as sr-robot3 does)."""
    path = Path(path)
    return path if path.suffix else path.with_suffix(".jpg")


class AprilCamera:
    """A camera that finds markers, as sr-robot3 shows it.

    If the game's marker sizes are not known to j5aio's camera (a webcam), sr-robot3's
    table of sizes is given to it. As in sr-robot3, a marker whose id has no size in the
    table is not reported.

    :param camera: j5aio's marker camera.
    :param serial_num: the camera's name.
    """

    __slots__ = ("_camera", "_serial_num")

    def __init__(self, camera: MarkerCamera, serial_num: str) -> None:
        self._camera = camera
        self._serial_num = serial_num
        if not camera.marker_sizes:
            camera.set_marker_sizes(marker_size_table())

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``Camera``."""
        return "Camera"

    def identify(self) -> BoardIdentity:
        """The camera's identity: its name is its asset tag."""
        from j5aio import __version__

        return BoardIdentity("j5aio", "camera", self._serial_num, __version__)

    def close(self) -> None:
        """Stop using the camera (j5aio closes it when the program ends)."""

    def see(self, *, frame: Any = None, save: PathLike | None = None) -> list[Marker]:
        """Take a picture (or use ``frame``) and return the markers in it, nearest first.

        :param frame: a picture to look in instead of taking one (a BGR numpy array).
        :param save: write the picture here with the markers outlined (``.jpg`` added
            when the name has no suffix).
        """
        from j5aio.vision.sizes import UnknownMarkerError

        try:
            if frame is None and save is None:
                try:
                    markers = self._camera.see()
                except UnknownMarkerError:  # (rare: then look at a picture of our own)
                    markers = self._known_markers(self._camera.capture())
            else:
                from j5aio.vision.annotate import annotate, write_image

                if frame is None:
                    frame = self._camera.capture()
                markers = self._known_markers(frame)
                if save:
                    write_image(_jpeg(save), annotate(frame, markers))
        except CommunicationError as error:
            raise disconnected(error) from error
        return [Marker.from_j5aio_marker(marker) for marker in markers]

    def _known_markers(self, frame: Any) -> list[CoreMarker]:
        """The markers in ``frame`` whose ids have a size, as sr-robot3 reports only those."""
        from j5aio.vision.detect import detect_marker_ids, detect_markers

        known = self._camera.marker_sizes
        sizes = {marker: known.get(marker, 1.0) for marker in detect_marker_ids(frame)}
        sizes.update(known)
        found = detect_markers(frame, self._camera.calibration, sizes)
        return [marker for marker in found if marker.id in known]

    def capture(self, *, save: PathLike | None = None) -> Any:
        """Take a picture and return it (a BGR numpy array).

        :param save: also write it here (``.jpg`` added when the name has no suffix).
        """
        try:
            frame = self._camera.capture()
        except CommunicationError as error:
            raise disconnected(error) from error
        if save:
            from j5aio.vision.annotate import write_image

            write_image(_jpeg(save), frame)
        return frame

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._serial_num}>"
