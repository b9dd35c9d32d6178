"""Camera backends: a webcam through OpenCV, and pictures from files or arrays.

The console and simulated cameras live with their environments
(:mod:`j5aio.backends.console.camera`, :mod:`j5aio.simulator.camera`).
"""

from j5aio.backends.camera.files import FileCameraBackend
from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.backends.camera.opencv import OpenCVCameraBackend

__all__ = ["FileCameraBackend", "FrameCameraBackend", "OpenCVCameraBackend"]
