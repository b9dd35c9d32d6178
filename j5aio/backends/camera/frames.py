"""FrameCameraBackend: the shared part of every camera backend that has real pictures.

A subclass says how to get one picture (:meth:`FrameCameraBackend.grab`, a blocking call);
this base runs it and the detector on the camera's own worker thread, so the event loop is
never blocked by a capture or a detection. Where the robot's service runs
(:mod:`j5aio.service`), each frame looked at is offered, annotated, to the robot's web
page, as sr-robot3 and sbot do.
"""

from __future__ import annotations

import sys
from abc import abstractmethod
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.backend import Backend
from j5aio.boards.camera import CameraBoard
from j5aio.components.marker_camera import MarkerCameraInterface

if TYPE_CHECKING:
    from j5aio.boards.board import Board
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.detect import MarkerDetector
    from j5aio.vision.image import Image
    from j5aio.vision.markers import Marker
    from j5aio.vision.sizes import MarkerSizes
    from j5aio.vision.worker import CameraWorker

__all__ = ["FrameCameraBackend"]


def _share_with_the_robot_service(frame: Image, markers: Sequence[Marker] | None) -> None:
    """Offer the frame, annotated, to the robot's web page if the robot service runs.

    Costs nothing without the service (its module is not even imported then); with it,
    the annotation is drawn only for a frame the service takes (see
    :func:`j5aio.service.service.publish_frame`).
    """
    service = sys.modules.get("j5aio.service.service")
    if service is None:
        return
    if markers is None:
        service.publish_frame(frame)
        return
    found = list(markers)

    def annotated() -> Image:
        from j5aio.vision.annotate import annotate

        return annotate(frame, found)

    service.publish_frame(annotated)


class FrameCameraBackend(Backend, MarkerCameraInterface):
    """A camera whose pictures come from :meth:`grab`, detected on a worker thread.

    :param name: the camera's name (the serial number of its board).
    :param calibration: the camera's calibration; ``None`` for ids and pixels only.
    :param quad_decimate: passed to the :class:`~j5aio.vision.detect.MarkerDetector`.
    """

    board: ClassVar[type[Board]] = CameraBoard

    def __init__(
        self,
        name: str,
        calibration: CameraCalibration | None = None,
        *,
        quad_decimate: float = 2.0,
    ) -> None:
        self._name = name
        self._calibration = calibration
        self._quad_decimate = quad_decimate
        self._detector: MarkerDetector | None = None
        # (made by the first look: every robot on the simulated kit has a camera, and
        # most programs never look through it)
        self._worker: CameraWorker | None = None
        self._closed = False

    @property
    def name(self) -> str:
        """The camera's name."""
        return self._name

    @property
    def firmware_version(self) -> None:
        """Always ``None``: a camera has no firmware j5aio knows of."""
        return None

    @abstractmethod
    def grab(self) -> Image:
        """Take one picture (blocking; runs on the worker thread).

        :raises CommunicationError: no picture could be had.
        """
        raise NotImplementedError

    def _worker_here(self) -> CameraWorker:
        """The camera's worker thread (:class:`~j5aio.vision.worker.CameraWorker`).

        :raises RuntimeError: the camera is closed.
        """
        if self._worker is None:
            if self._closed:
                raise RuntimeError("this camera is closed")
            from j5aio.vision.worker import CameraWorker

            self._worker = CameraWorker(f"camera {self._name}")
        return self._worker

    def _detector_here(self) -> MarkerDetector:
        # Made on the worker thread, the only thread that uses it.
        if self._detector is None:
            from j5aio.vision.detect import MarkerDetector  # (here: the first look needs it)

            self._detector = MarkerDetector(quad_decimate=self._quad_decimate)
        return self._detector

    async def frame_source(self) -> Callable[[], Image]:
        """Return the blocking call that takes the next picture on the worker thread.

        :meth:`grab` by default; a simulated camera first notes, on the event loop, where
        the robot is, and returns a call that renders that view.
        """
        return self.grab

    def _see(self, source: Callable[[], Image], sizes: MarkerSizes) -> list[Marker]:
        frame = source()
        markers = self._detector_here().detect(frame, self._calibration, sizes)
        _share_with_the_robot_service(frame, markers)
        return markers

    def _see_ids(self, source: Callable[[], Image]) -> list[int]:
        return self._detector_here().detect_ids(source())

    def _save(self, source: Callable[[], Image], path: Path, sizes: MarkerSizes) -> None:
        from j5aio.vision.annotate import annotate, write_image

        frame = source()
        markers = self._detector_here().detect(frame, self._calibration, sizes)
        annotated = annotate(frame, markers)
        write_image(path, annotated)
        _share_with_the_robot_service(annotated, None)

    async def see_markers(self, identifier: int, marker_sizes: MarkerSizes) -> list[Marker]:
        """Take a picture and return the markers in it, nearest first."""
        return await self._worker_here().run(self._see, await self.frame_source(), marker_sizes)

    async def see_marker_ids(self, identifier: int) -> list[int]:
        """Take a picture and return the ids of the markers in it, sorted."""
        return await self._worker_here().run(self._see_ids, await self.frame_source())

    async def capture_frame(self, identifier: int) -> Image:
        """Take a picture and return it."""
        return await self._worker_here().run(await self.frame_source())

    async def save_annotated_frame(
        self, identifier: int, path: Path, marker_sizes: MarkerSizes
    ) -> None:
        """Take a picture, outline the markers found, and write it to ``path``."""
        await self._worker_here().run(self._save, await self.frame_source(), path, marker_sizes)

    async def get_calibration(self, identifier: int) -> CameraCalibration | None:
        """Return the camera's calibration, or ``None``."""
        return self._calibration

    async def close(self) -> None:
        """Stop the camera's worker thread (and release the device, in subclasses)."""
        self._closed = True
        if self._worker is not None:
            self._worker.close()
