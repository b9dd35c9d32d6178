"""Camera backends: a webcam through OpenCV, and pictures from files or arrays.

The console and simulated cameras live with their environments
(:mod:`j5aio.backends.console.camera`, :mod:`j5aio.simulator.camera`).
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.camera.files import FileCameraBackend as FileCameraBackend
    from j5aio.backends.camera.frames import FrameCameraBackend as FrameCameraBackend
    from j5aio.backends.camera.opencv import OpenCVCameraBackend as OpenCVCameraBackend

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.camera.files": ["FileCameraBackend"],
            "j5aio.backends.camera.frames": ["FrameCameraBackend"],
            "j5aio.backends.camera.opencv": ["OpenCVCameraBackend"],
        },
    )
