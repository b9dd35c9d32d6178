"""Camera backends: a webcam through OpenCV, and pictures from files or arrays.

The console and simulated cameras live with their environments
(:mod:`j5aio.backends.console.camera`, :mod:`j5aio.simulator.camera`).
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.camera.files import FileCameraBackend
    from j5aio.backends.camera.frames import FrameCameraBackend
    from j5aio.backends.camera.opencv import OpenCVCameraBackend

__all__ = ["FileCameraBackend", "FrameCameraBackend", "OpenCVCameraBackend"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.camera.files": ["FileCameraBackend"],
            "j5aio.backends.camera.frames": ["FrameCameraBackend"],
            "j5aio.backends.camera.opencv": ["OpenCVCameraBackend"],
        },
    )
