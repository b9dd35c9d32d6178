"""MarkerCamera: a camera that finds AprilTag 36h11 markers (needs ``j5aio[vision]``).

::

    markers = await robot.camera.see()
    for marker in markers:
        print(marker.id, marker.position.distance, marker.position.horizontal_angle)

This module imports neither numpy nor OpenCV: backends import them when a camera is used.
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from j5aio.components._marker_sizes import MarkerSizes
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

if TYPE_CHECKING:
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image
    from j5aio.vision.markers import Marker

__all__ = ["MarkerCamera", "MarkerCameraInterface"]

_IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff")


class MarkerCameraInterface(Interface):
    """The coroutines a backend implements for a marker camera.

    Capturing and detecting must not block the event loop (run them on a worker thread).
    """

    @abstractmethod
    async def see_markers(self, identifier: int, marker_sizes: MarkerSizes) -> list[Marker]:
        """Take a picture and return the markers in it, nearest first."""
        raise NotImplementedError

    @abstractmethod
    async def see_marker_ids(self, identifier: int) -> list[int]:
        """Take a picture and return the ids of the markers in it, sorted."""
        raise NotImplementedError

    @abstractmethod
    async def capture_frame(self, identifier: int) -> Image:
        """Take a picture and return it (BGR)."""
        raise NotImplementedError

    @abstractmethod
    async def save_annotated_frame(
        self, identifier: int, path: Path, marker_sizes: MarkerSizes
    ) -> None:
        """Take a picture, mark the markers found on it, and write it to ``path``."""
        raise NotImplementedError

    @abstractmethod
    async def get_calibration(self, identifier: int) -> CameraCalibration | None:
        """Return the camera's calibration, or ``None`` if it has none."""
        raise NotImplementedError


class MarkerCamera(IdentifiedComponent[MarkerCameraInterface]):
    """A camera that finds fiducial markers (AprilTag 36h11) and says where they are.

    :param identifier: the number of the camera on its board.
    :param backend: the backend that takes the pictures.
    :param marker_sizes: the game's table of marker sizes (ids to mm); set it later with
        :meth:`set_marker_sizes`. Until then, every marker seen is an error.
    """

    __slots__ = ("_marker_sizes",)

    def __init__(
        self,
        identifier: int,
        backend: MarkerCameraInterface,
        marker_sizes: Mapping[int, float] | None = None,
    ) -> None:
        super().__init__(identifier, backend)
        # (a table is kept as it is, unread: a simulated arena's is read on first use)
        self._marker_sizes = (
            marker_sizes if isinstance(marker_sizes, MarkerSizes) else MarkerSizes(marker_sizes)
        )

    @classmethod
    def interface_class(cls) -> type[MarkerCameraInterface]:
        """The interface a backend implements: :class:`MarkerCameraInterface`."""
        return MarkerCameraInterface

    @property
    def marker_sizes(self) -> MarkerSizes:
        """The game's table of marker sizes, id to mm."""
        return self._marker_sizes

    def set_marker_sizes(self, marker_sizes: Mapping[int, float]) -> None:
        """Set the game's table of marker sizes (ids to mm), as the competition says.

        :raises TypeError: not a mapping of int ids to numbers.
        :raises ValueError: an id is outside AprilTag 36h11, or a size is not above 0.
        """
        if not isinstance(marker_sizes, Mapping):
            raise TypeError(
                "marker_sizes must be a MarkerSizes or a dict of marker ids to sizes in mm, "
                f"not {type(marker_sizes).__name__}",
            )
        self._marker_sizes = (
            marker_sizes if isinstance(marker_sizes, MarkerSizes) else MarkerSizes(marker_sizes)
        )

    async def get_calibration(self) -> CameraCalibration | None:
        """Return the camera's calibration; ``None`` means distances are unknown."""
        return await self._backend.get_calibration(self._identifier)

    async def see(self) -> list[Marker]:
        """Take a picture and return the markers in it, nearest first.

        Without a calibration each marker has its id and pixels, and NaN distances and
        angles (``marker.has_pose`` is ``False``).

        :raises UnknownMarkerError: a marker was seen whose id has no size in the table.
        :raises ~j5aio.vision.VisionNotInstalledError: the vision libraries are not installed.
        :raises CommunicationError: the camera gave no picture.
        """
        return await self._backend.see_markers(self._identifier, self._marker_sizes)

    async def see_ids(self) -> list[int]:
        """Take a picture and return the ids of the markers in it (fast: no distances).

        :raises CommunicationError: the camera gave no picture.
        """
        return await self._backend.see_marker_ids(self._identifier)

    async def capture(self) -> Image:
        """Take a picture and return it: a numpy array, height x width x 3, BGR.

        :raises CommunicationError: the camera gave no picture.
        """
        return await self._backend.capture_frame(self._identifier)

    async def save(self, path: str | Path) -> None:
        """Take a picture and write it to ``path``, with the markers found outlined.

        :param path: where to write; the suffix (``.png``, ``.jpg``...) picks the format.
        :raises TypeError: ``path`` is not a str or a Path.
        :raises ValueError: ``path`` has no image suffix OpenCV can write.
        :raises CommunicationError: the camera gave no picture.
        """
        if not isinstance(path, str | Path):
            raise TypeError(f"path must be a str or a Path, not {type(path).__name__}")
        path = Path(path)
        if path.suffix.lower() not in _IMAGE_SUFFIXES:
            raise ValueError(
                f"cannot tell the image format of {str(path)!r}: give it one of the suffixes "
                + ", ".join(_IMAGE_SUFFIXES),
            )
        await self._backend.save_annotated_frame(self._identifier, path, self._marker_sizes)
