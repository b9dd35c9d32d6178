"""Rendering what a calibrated pinhole camera sees: flat quads and AprilTag 36h11 markers.

Everything is given in OpenCV's camera frame (x right, y down, z forwards, mm). The
renderer draws flat coloured quads (walls, floor, the faces of tokens) clipped at a near
plane, then each marker as a texture warped by the homography of its four projected
corners. Objects are drawn in the order given (painter's order: far first).

Markers are drawn the right way up: OpenCV's own marker images of this family are turned
180° from the official AprilTag layout, so they are turned back here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from j5aio.vision._optional import require
from j5aio.vision.geometry import Matrix3, Vector3

if TYPE_CHECKING:
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image

__all__ = ["Lighting", "MarkerItem", "QuadItem", "render"]

#: Closest distance drawn, mm: anything nearer the camera is clipped away.
NEAR_PLANE = 10.0

# Cells of a 36h11 marker: 6 data cells, a black border cell each side, a white border.
_BLACK_CELLS = 8
_TOTAL_CELLS = 10

# A marker whose longest edge is under so many pixels is drawn so many times finer.
_SUPERSAMPLING = ((4, 80.0), (2, 200.0))


@dataclass(frozen=True)
class QuadItem:
    """A flat four-cornered surface of one colour (BGR), corners in camera coordinates."""

    corners: tuple[Vector3, Vector3, Vector3, Vector3]
    colour: tuple[int, int, int]


@dataclass(frozen=True)
class MarkerItem:
    """A marker: its centre and rotation (marker frame to camera frame) and size in mm.

    ``size`` is the edge of the black square; a white border one cell wide surrounds it.
    """

    marker_id: int
    size: float
    centre: Vector3
    rotation: Matrix3

    def corners(self, scale: float) -> list[Vector3]:
        """Top-left, top-right, bottom-right, bottom-left, ``scale`` times the size."""
        half = self.size * scale / 2
        r = self.rotation
        points = []
        for mx, my in ((-half, -half), (half, -half), (half, half), (-half, half)):
            points.append(
                (
                    self.centre[0] + r[0][0] * mx + r[0][1] * my,
                    self.centre[1] + r[1][0] * mx + r[1][1] * my,
                    self.centre[2] + r[2][0] * mx + r[2][1] * my,
                )
            )
        return points


@dataclass(frozen=True)
class Lighting:
    """How a rendered picture differs from a perfect one.

    :param brightness: multiplies every pixel (1.0: as drawn).
    :param gradient: the fraction by which the light falls off from the left edge of the
        picture to the right (0: even light).
    :param blur: the sigma of a Gaussian blur, pixels (0: sharp).
    :param noise: the standard deviation of Gaussian noise added to each pixel, in grey
        levels (0: none).
    :param seed: the seed of the noise, so that a picture can be made again.
    """

    brightness: float = 1.0
    gradient: float = 0.0
    blur: float = 0.0
    noise: float = 0.0
    seed: int = 0


_texture_cache: dict[tuple[int, int], Any] = {}


def _marker_texture(marker_id: int, cell: int) -> Any:
    """The marker with its white border, ``cell`` pixels a cell, upright."""
    key = (marker_id, cell)
    texture = _texture_cache.get(key)
    if texture is None:
        np, cv2 = require("numpy"), require("cv2")
        dictionary = cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_APRILTAG_36h11)
        cells = dictionary.generateImageMarker(marker_id, _BLACK_CELLS)
        cells = np.rot90(cells, 2)  # OpenCV draws this family upside down
        bordered = np.full((_TOTAL_CELLS, _TOTAL_CELLS), 255, dtype=np.uint8)
        bordered[1:-1, 1:-1] = cells
        texture = np.kron(bordered, np.ones((cell, cell), dtype=np.uint8))
        _texture_cache[key] = texture
    return texture


def _project(
    points: Sequence[Vector3], calibration: CameraCalibration
) -> list[tuple[float, float]]:
    return [
        (calibration.fx * x / z + calibration.cx, calibration.fy * y / z + calibration.cy)
        for x, y, z in points
    ]


def _clip_near(points: Sequence[Vector3]) -> list[Vector3]:
    """Clip a polygon to the half-space in front of the near plane (Sutherland-Hodgman)."""
    out: list[Vector3] = []
    count = len(points)
    for i in range(count):
        a, b = points[i], points[(i + 1) % count]
        a_in, b_in = a[2] >= NEAR_PLANE, b[2] >= NEAR_PLANE
        if a_in:
            out.append(a)
        if a_in != b_in:
            t = (NEAR_PLANE - a[2]) / (b[2] - a[2])
            out.append(
                (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), NEAR_PLANE),
            )
    return out


def render(
    calibration: CameraCalibration,
    resolution: tuple[int, int],
    items: Sequence[QuadItem | MarkerItem],
    *,
    background: tuple[int, int, int] = (200, 200, 200),
    lighting: Lighting | None = None,
) -> Image:
    """Return the BGR picture that the camera sees of ``items``, drawn in the order given.

    The calibration's distortion is not applied: the picture is that of a perfect pinhole.

    :param calibration: the camera's pinhole model.
    :param resolution: ``(width, height)`` of the picture.
    :param items: what to draw, far things first.
    :param background: the colour where nothing is drawn.
    :param lighting: brightness, blur and noise; none by default.
    """
    np = require("numpy")
    width, height = resolution
    frame = np.empty((height, width, 3), dtype=np.uint8)
    frame[:] = background
    for item in items:
        if isinstance(item, QuadItem):
            _draw_quad(frame, item, calibration)
        else:
            _draw_marker(frame, item, calibration)
    if lighting is not None:
        frame = _light(frame, lighting)
    return frame  # type: ignore[no-any-return]


def _draw_quad(frame: Any, quad: QuadItem, calibration: CameraCalibration) -> None:
    np, cv2 = require("numpy"), require("cv2")
    clipped = _clip_near(quad.corners)
    if len(clipped) < 3:
        return
    # Far-away points project far outside the picture: clamp them to keep the
    # fixed-point polygon filler in range.
    limit = 4 * max(frame.shape)
    projected = [
        (max(-limit, min(limit, u)), max(-limit, min(limit, v)))
        for u, v in _project(clipped, calibration)
    ]
    shift = 4
    points = np.round(np.array(projected) * (1 << shift)).astype(np.int32)
    cv2.fillPoly(frame, [points], quad.colour, lineType=cv2.LINE_AA, shift=shift)


def _draw_marker(frame: Any, marker: MarkerItem, calibration: CameraCalibration) -> None:
    np, cv2 = require("numpy"), require("cv2")
    outer = marker.corners(_TOTAL_CELLS / _BLACK_CELLS)
    if min(p[2] for p in outer) < NEAR_PLANE:
        return
    # The marker must face the camera to be seen.
    if _dot(marker.centre, _normal(marker.rotation)) <= 0:
        return
    projected = np.array(_project(outer, calibration), dtype=np.float32)
    height, width = frame.shape[:2]
    x0 = max(0, math.floor(float(projected[:, 0].min())) - 1)
    y0 = max(0, math.floor(float(projected[:, 1].min())) - 1)
    x1 = min(width, math.ceil(float(projected[:, 0].max())) + 2)
    y1 = min(height, math.ceil(float(projected[:, 1].max())) + 2)
    if x0 >= x1 or y0 >= y1:
        return
    edge = max(
        math.dist(tuple(projected[i]), tuple(projected[(i + 1) % 4])) for i in range(4)
    )
    size = (x1 - x0, y1 - y0)
    factor = _supersampling(edge)
    cell = max(1, min(64, math.ceil(factor * edge / _TOTAL_CELLS)))
    texture = _marker_texture(marker.marker_id, cell)
    side = texture.shape[0]
    # Texel centres sit at integer coordinates, so the texture's edges are at -0.5.
    source = np.array(
        [[-0.5, -0.5], [side - 0.5, -0.5], [side - 0.5, side - 0.5], [-0.5, side - 0.5]],
        dtype=np.float32,
    )
    target = projected - np.array([x0, y0], dtype=np.float32)
    # Drawn ``factor`` times finer, then each pixel is the mean of its ``factor`` x
    # ``factor`` block, as a camera's pixel sums the light falling on its area. (Sampling
    # the texture once per pixel would move the marker's edges by up to a tenth of a
    # pixel, which is all a small marker's perspective has to tell its pose by.)
    fine_target = (target + 0.5) * factor - 0.5
    homography = cv2.getPerspectiveTransform(source, fine_target)
    warped = cv2.warpPerspective(
        texture,
        homography,
        (size[0] * factor, size[1] * factor),
        flags=cv2.INTER_LINEAR,
        borderMode=cv2.BORDER_REPLICATE,
    )
    if factor > 1:
        warped = cv2.resize(warped, size, interpolation=cv2.INTER_AREA)
    mask = np.zeros((size[1], size[0]), dtype=np.uint8)
    shift = 4
    points = np.round(target * (1 << shift)).astype(np.int32)
    cv2.fillConvexPoly(mask, points, 255, lineType=cv2.LINE_AA, shift=shift)
    alpha = mask.astype(np.float32)[:, :, None] / 255.0
    region = frame[y0:y1, x0:x1].astype(np.float32)
    blended = region * (1.0 - alpha) + warped.astype(np.float32)[:, :, None] * alpha
    frame[y0:y1, x0:x1] = np.clip(blended + 0.5, 0, 255).astype(np.uint8)


def _supersampling(edge: float) -> int:
    """How many times finer a marker whose longest edge is ``edge`` pixels is drawn.

    Small markers need it most (a tenth of a pixel is much of what their perspective
    tells) and cost least; a large one is drawn once a pixel.
    """
    for factor, below in _SUPERSAMPLING:
        if edge < below:
            return factor
    return 1


def _normal(rotation: Matrix3) -> Vector3:
    """The marker's z axis (into its face) in camera coordinates."""
    return (rotation[0][2], rotation[1][2], rotation[2][2])


def _dot(a: Vector3, b: Vector3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _light(frame: Any, lighting: Lighting) -> Any:
    np, cv2 = require("numpy"), require("cv2")
    result = frame.astype(np.float32) * lighting.brightness
    if lighting.gradient:
        width = frame.shape[1]
        ramp = 1.0 - lighting.gradient * np.linspace(0.0, 1.0, width, dtype=np.float32)
        result *= ramp[None, :, None]
    if lighting.blur > 0:
        result = cv2.GaussianBlur(result, (0, 0), lighting.blur)
    if lighting.noise > 0:
        rng = np.random.default_rng(lighting.seed)
        result += rng.normal(0.0, lighting.noise, result.shape).astype(np.float32)
    return np.clip(result + 0.5, 0, 255).astype(np.uint8)
