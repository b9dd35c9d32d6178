"""Finding AprilTag 36h11 markers in a picture: the one detector every camera backend uses.

Detection is by the AprilTag 3 C library (through pyapriltags); the pose of each marker
comes from OpenCV's ``solvePnP`` with the IPPE method for planar squares, on the corners
the AprilTag library refined, choosing between the two poses a flat square fits by the rule
of :func:`choose_pose`; the result is turned into sr-robot3's axes and names by
:mod:`j5aio.vision.geometry`.
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from j5aio.vision._optional import require
from j5aio.vision.geometry import orientation_from_rotation, position_from_translation
from j5aio.vision.markers import Marker, PixelCoordinates
from j5aio.vision.sizes import MarkerSizes

if TYPE_CHECKING:
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image

__all__ = [
    "AMBIGUITY_RATIO",
    "ERROR_FLOOR",
    "POOR_FIT",
    "MarkerDetector",
    "PoseCandidate",
    "choose_pose",
    "detect_marker_ids",
    "detect_markers",
]

#: The marker family every SR and SourceBots game uses.
FAMILY = "tag36h11"

#: Two poses are told apart by their fit only when the worse one's RMS reprojection error
#: is more than this many times the better one's (plus :data:`ERROR_FLOOR`).
AMBIGUITY_RATIO = 1.2

#: A pose whose corners reproject worse than this (RMS, pixels) is not a fit of them.
POOR_FIT = 1.0

#: Reprojection errors (pixels) within this of each other are equal, however small both are.
ERROR_FLOOR = 0.002


@dataclass(frozen=True)
class PoseCandidate:
    """One of the two poses of a planar marker that fit its corners.

    :param error: the RMS reprojection error of the marker's corners, pixels.
    :param normal_down: the downward (OpenCV y) part of the unit normal of the marker's
        face, in the camera's frame: 0 for a face that is vertical to a level camera.
    :param rvec: the rotation (a Rodrigues vector), as OpenCV gives it.
    :param tvec: the translation, mm, as OpenCV gives it.
    """

    error: float
    normal_down: float
    rvec: Any
    tvec: Any


def choose_pose(candidates: Sequence[PoseCandidate]) -> PoseCandidate:
    """Choose the pose of a marker among the poses that fit its four corners.

    A flat square seen in perspective fits two poses (IPPE gives both): the true one and
    its mirror image about the line of sight, whose face is tilted the other way by about
    the same angle. Perspective tells them apart: the far edge of the square is shorter
    than the near one, so after both are polished (Levenberg-Marquardt on the corners),
    the true pose reprojects the corners better. The rule:

    1. the pose with the smaller reprojection error is chosen when the other's error is
       more than :data:`AMBIGUITY_RATIO` times larger (plus :data:`ERROR_FLOOR` pixels);
    2. otherwise the fit cannot tell them apart, and the pose whose face is nearer
       vertical is chosen (markers on walls and on the sides of tokens are vertical, and
       a robot's camera looks level); on a tie, the better fit.

    Limits: the difference between the two fits shrinks with the marker's size in the
    picture and with how obliquely it is seen. On clean 1280x720 pictures of 150 mm
    markers it stays well above the ratio up to 6 m (about 35 px); with a real camera's
    noise, a marker under about 30 px wide can still be given its mirror orientation when
    rule 2 applies to a marker that is not vertical (for instance on top of a token). When
    the marker is seen face-on, the two poses are the same and either is right. Distance
    and bearing do not depend on the choice.

    :param candidates: one or two poses.
    :returns: the chosen pose.
    :raises ValueError: there is no pose to choose from.
    """
    if not candidates:
        raise ValueError("choose_pose needs at least one pose, got none")
    ordered = sorted(candidates, key=lambda c: c.error)
    best = ordered[0]
    if len(ordered) == 1 or ordered[1].error > AMBIGUITY_RATIO * best.error + ERROR_FLOOR:
        return best
    return min(ordered[:2], key=lambda c: abs(c.normal_down))


def _as_sizes(marker_sizes: Mapping[int, float] | MarkerSizes) -> MarkerSizes:
    if isinstance(marker_sizes, MarkerSizes):
        return marker_sizes
    if not isinstance(marker_sizes, Mapping):
        raise TypeError(
            "marker_sizes must be a MarkerSizes or a mapping of marker ids to sizes in mm, "
            f"not {type(marker_sizes).__name__}",
        )
    return MarkerSizes(marker_sizes)


class MarkerDetector:
    """An AprilTag 36h11 detector with its settings. Not thread-safe: one per thread.

    :param quad_decimate: detect the outlines on a picture this many times smaller (faster;
        the corners are then refined on the full picture). 1 finds the smallest markers.
    :param threads: threads the AprilTag library uses for one picture.
    :param max_hamming: accept ids this many bits away from a valid code (0 or 1; 0 never
        reports a wrong id).
    :raises ~j5aio.vision.VisionNotInstalledError: the vision libraries are not installed.
    """

    def __init__(
        self, *, quad_decimate: float = 2.0, threads: int | None = None, max_hamming: int = 0
    ) -> None:
        if not quad_decimate >= 1:
            raise ValueError(f"quad_decimate must be 1 or more, not {quad_decimate}")
        if max_hamming not in (0, 1):
            raise ValueError(f"max_hamming must be 0 or 1, not {max_hamming}")
        self._np = require("numpy")
        self._cv2 = require("cv2")
        apriltags = require("pyapriltags")
        if threads is None:
            threads = min(4, os.cpu_count() or 1)
        self._max_hamming = max_hamming
        self._detector = apriltags.Detector(
            families=FAMILY, nthreads=threads, quad_decimate=quad_decimate, refine_edges=1
        )

    def _grey(self, image: Image) -> Any:
        np, cv2 = self._np, self._cv2
        if not isinstance(image, np.ndarray):
            raise TypeError(f"image must be a numpy array, not {type(image).__name__}")
        if image.dtype != np.uint8:
            raise TypeError(f"image must hold uint8 pixels, not {image.dtype}")
        if image.ndim == 2:
            grey = image
        elif image.ndim == 3 and image.shape[2] == 3:
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
        elif image.ndim == 3 and image.shape[2] == 4:
            grey = cv2.cvtColor(image, cv2.COLOR_BGRA2GRAY)
        elif image.ndim == 3 and image.shape[2] == 1:
            grey = image[:, :, 0]
        else:
            raise ValueError(
                f"image must be greyscale (H x W) or BGR (H x W x 3), not shape {image.shape}"
            )
        return np.ascontiguousarray(grey)

    def _raw(self, image: Image) -> list[Any]:
        detections = self._detector.detect(self._grey(image))
        return [d for d in detections if d.hamming <= self._max_hamming]

    def detect_ids(self, image: Image) -> list[int]:
        """Return the ids of the markers in ``image``, without working out where they are."""
        return sorted(int(d.tag_id) for d in self._raw(image))

    def detect(
        self,
        image: Image,
        calibration: CameraCalibration | None,
        marker_sizes: Mapping[int, float] | MarkerSizes,
    ) -> list[Marker]:
        """Return the markers in ``image``, nearest first (by id when there is no pose).

        See :func:`detect_markers`.
        """
        sizes = _as_sizes(marker_sizes)
        detections = self._raw(image)
        markers = [self._marker(d, calibration, sizes) for d in detections]
        if calibration is None:
            return sorted(markers, key=lambda m: m.id)
        return sorted(markers, key=lambda m: (m.position.distance, m.id))

    def _solve_pose(
        self, object_points: Any, image_points: Any, camera_matrix: Any, distortion: Any
    ) -> tuple[Any, Any]:
        """The marker's pose: the better of IPPE's two, each polished. See :func:`choose_pose`.

        OpenCV's IPPE is fragile on corners that are exactly symmetric about a row or column
        through the principal point (as a rendered marker at the camera's height can be):
        both its poses then miss the corners by tens of pixels. When the better polished
        pose still misses them by more than :data:`POOR_FIT`, SQPnP's (a global minimum of
        the reprojection error) is polished and considered too.
        """
        cv2 = self._cv2
        _, rvecs, tvecs, _ = cv2.solvePnPGeneric(
            object_points, image_points, camera_matrix, distortion, flags=cv2.SOLVEPNP_IPPE
        )
        fit = (object_points, image_points, camera_matrix, distortion)
        candidates = [self._polish(*fit, r, t) for r, t in zip(rvecs, tvecs, strict=True)]
        if min(c.error for c in candidates) > POOR_FIT:
            _, rvecs, tvecs, _ = cv2.solvePnPGeneric(*fit, flags=cv2.SOLVEPNP_SQPNP)
            candidates += [self._polish(*fit, r, t) for r, t in zip(rvecs, tvecs, strict=True)]
        chosen = choose_pose(candidates)
        return chosen.rvec, chosen.tvec

    def _polish(
        self,
        object_points: Any,
        image_points: Any,
        camera_matrix: Any,
        distortion: Any,
        rvec: Any,
        tvec: Any,
    ) -> PoseCandidate:
        """Refine a pose by Levenberg-Marquardt on the corners, and measure its fit."""
        np, cv2 = self._np, self._cv2
        rvec, tvec = cv2.solvePnPRefineLM(
            object_points, image_points, camera_matrix, distortion, rvec, tvec
        )
        projected, _ = cv2.projectPoints(object_points, rvec, tvec, camera_matrix, distortion)
        residual = projected.reshape(-1, 2) - image_points
        error = math.sqrt(float(np.mean(np.sum(residual**2, axis=1))))
        rotation, _ = cv2.Rodrigues(rvec)
        return PoseCandidate(error, float(rotation[1][2]), rvec, tvec)

    def _marker(
        self,
        detection: Any,
        calibration: CameraCalibration | None,
        sizes: MarkerSizes,
    ) -> Marker:
        marker_id = int(detection.tag_id)
        size = sizes.size_of(marker_id)
        # The AprilTag library puts pixel centres at +0.5; OpenCV (and this API) at 0.
        corners = detection.corners - 0.5
        pixel_corners = tuple(PixelCoordinates(float(x), float(y)) for x, y in corners)
        centre = PixelCoordinates(
            float(detection.center[0]) - 0.5, float(detection.center[1]) - 0.5
        )
        if calibration is None:
            return Marker(marker_id, size, centre, pixel_corners)  # type: ignore[arg-type]
        np, cv2 = self._np, self._cv2
        half = size / 2
        # The detector's corners, in the marker's own frame (x right, y down its face):
        # bottom-left, bottom-right, top-right, top-left.
        object_points = np.array(
            [[-half, half, 0], [half, half, 0], [half, -half, 0], [-half, -half, 0]],
            dtype=np.float64,
        )
        camera_matrix = np.array(
            [[calibration.fx, 0, calibration.cx], [0, calibration.fy, calibration.cy], [0, 0, 1]],
            dtype=np.float64,
        )
        distortion = np.array(calibration.distortion, dtype=np.float64)
        image_points = np.asarray(corners, dtype=np.float64)
        rvec, tvec = self._solve_pose(object_points, image_points, camera_matrix, distortion)
        rotation, _ = cv2.Rodrigues(rvec)
        position, cartesian = position_from_translation(tvec.ravel().tolist())
        orientation = orientation_from_rotation(rotation.tolist())
        return Marker(
            marker_id,
            size,
            centre,
            pixel_corners,  # type: ignore[arg-type]
            position,
            cartesian,
            orientation,
        )


_local = threading.local()


def _thread_detector() -> MarkerDetector:
    detector: MarkerDetector | None = getattr(_local, "detector", None)
    if detector is None:
        detector = _local.detector = MarkerDetector()
    return detector


def detect_markers(
    image: Image,
    calibration: CameraCalibration | None,
    marker_sizes: Mapping[int, float] | MarkerSizes,
) -> list[Marker]:
    """Find the AprilTag 36h11 markers in a picture.

    :param image: the picture, a numpy array of uint8: greyscale (H x W) or BGR
        (H x W x 3, as OpenCV reads and captures them).
    :param calibration: the camera's calibration; ``None`` finds ids and pixels only
        (every distance and angle is then NaN).
    :param marker_sizes: the game's table of marker sizes, id to mm.
    :returns: the markers found, nearest first (sorted by id without a calibration).
    :raises TypeError: ``image`` is not a uint8 numpy array.
    :raises ValueError: ``image`` has a shape that is not a picture.
    :raises UnknownMarkerError: a marker was found whose id has no size in the table.
    :raises ~j5aio.vision.VisionNotInstalledError: the vision libraries are not installed.
    """
    return _thread_detector().detect(image, calibration, marker_sizes)


def detect_marker_ids(image: Image) -> list[int]:
    """Return the ids of the markers in a picture, sorted (the fast path: no pose)."""
    return _thread_detector().detect_ids(image)
