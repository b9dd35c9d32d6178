"""A camera, as a board with one component: its :class:`.MarkerCamera`."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.board import Board
from j5aio.components.marker_camera import MarkerCamera, MarkerCameraInterface

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["CameraBoard"]


class CameraBoard(Board):
    """A camera plugged into the robot: a webcam, a file of pictures, or a simulated one.

    :param serial_number: the camera's name (its device path, or its place in a kit).
    :param backend: the backend that takes its pictures; if it has a ``marker_sizes``
        attribute (a simulated arena knows its markers), the camera starts with that table.
    """

    name: ClassVar[str] = "Camera"

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._camera = MarkerCamera(
            0, cast(MarkerCameraInterface, backend), getattr(backend, "marker_sizes", None)
        )

    @property
    def camera(self) -> MarkerCamera:
        """The camera's marker finder: ``await board.camera.see()``."""
        return self._camera

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes of a camera: :class:`.MarkerCamera`."""
        return {MarkerCamera}

    async def make_safe(self) -> None:
        """Do nothing: a camera has nothing to stop."""
