"""Vision: finding AprilTag 36h11 markers with a camera (the optional extra ``j5aio[vision]``).

:func:`~j5aio.vision.detect.detect_markers` does the finding for every camera backend; a
:class:`~j5aio.components.marker_camera.MarkerCamera` component gives robots ``see()``.
This package imports without the optional libraries (numpy, OpenCV, pyapriltags); the
first thing that needs them raises :class:`~j5aio.vision.VisionNotInstalledError` saying what to
install.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.vision._optional import INSTALL_HINT, VisionNotInstalledError
    from j5aio.vision.calibration import KNOWN_CALIBRATIONS, CameraCalibration, known_calibration
    from j5aio.vision.detect import MarkerDetector, detect_marker_ids, detect_markers
    from j5aio.vision.image import Image
    from j5aio.vision.markers import Cartesian, Marker, Orientation, PixelCoordinates, Position
    from j5aio.vision.sizes import MarkerSizes, UnknownMarkerError

__all__ = [
    "INSTALL_HINT",
    "KNOWN_CALIBRATIONS",
    "CameraCalibration",
    "Cartesian",
    "Image",
    "Marker",
    "MarkerDetector",
    "MarkerSizes",
    "Orientation",
    "PixelCoordinates",
    "Position",
    "UnknownMarkerError",
    "VisionNotInstalledError",
    "detect_marker_ids",
    "detect_markers",
    "known_calibration",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.vision._optional": ["INSTALL_HINT", "VisionNotInstalledError"],
            "j5aio.vision.calibration": [
                "CameraCalibration",
                "KNOWN_CALIBRATIONS",
                "known_calibration",
            ],
            "j5aio.vision.detect": ["MarkerDetector", "detect_marker_ids", "detect_markers"],
            "j5aio.vision.image": ["Image"],
            "j5aio.vision.markers": [
                "Cartesian",
                "Marker",
                "Orientation",
                "PixelCoordinates",
                "Position",
            ],
            "j5aio.vision.sizes": ["MarkerSizes", "UnknownMarkerError"],
        },
    )
