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
    from j5aio.vision._optional import INSTALL_HINT as INSTALL_HINT
    from j5aio.vision._optional import VisionNotInstalledError as VisionNotInstalledError
    from j5aio.vision.calibration import KNOWN_CALIBRATIONS as KNOWN_CALIBRATIONS
    from j5aio.vision.calibration import CameraCalibration as CameraCalibration
    from j5aio.vision.calibration import known_calibration as known_calibration
    from j5aio.vision.detect import MarkerDetector as MarkerDetector
    from j5aio.vision.detect import detect_marker_ids as detect_marker_ids
    from j5aio.vision.detect import detect_markers as detect_markers
    from j5aio.vision.image import Image as Image
    from j5aio.vision.markers import Cartesian as Cartesian
    from j5aio.vision.markers import Marker as Marker
    from j5aio.vision.markers import Orientation as Orientation
    from j5aio.vision.markers import PixelCoordinates as PixelCoordinates
    from j5aio.vision.markers import Position as Position
    from j5aio.vision.sizes import MarkerSizes as MarkerSizes
    from j5aio.vision.sizes import UnknownMarkerError as UnknownMarkerError

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
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
