"""The pure geometry between OpenCV's camera frame and the student's frame (no numpy).

OpenCV's camera frame has x to the right, y down and z forwards. A marker's own frame (as
AprilTag defines it) has x to the marker's right, y down its face and z into it, so a
marker facing the camera squarely, upright, has the identity rotation.

The student's frame (``Cartesian``) has x forwards, y left and z up. Orientation angles are
taken in the frame ``M`` that the marker's rotation is moved into (forward axis = -z,
left-right axis = -x, vertical axis = y of OpenCV), then split as
``R' = Rx(roll) · Ry(pitch) · Rz(yaw)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from j5aio.vision.markers import Cartesian, Orientation, Position

__all__ = [
    "Matrix3",
    "Vector3",
    "matmul",
    "orientation_from_rotation",
    "position_from_translation",
    "rotation_from_orientation",
    "transpose",
]

Vector3 = tuple[float, float, float]
Matrix3 = tuple[Vector3, Vector3, Vector3]

# The change of frame from OpenCV's axes to the axes the angles are measured in.
_M: Matrix3 = ((0.0, 0.0, -1.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0))


def transpose(a: Sequence[Sequence[float]]) -> Matrix3:
    """Return the transpose of a 3x3 matrix."""
    return (
        (a[0][0], a[1][0], a[2][0]),
        (a[0][1], a[1][1], a[2][1]),
        (a[0][2], a[1][2], a[2][2]),
    )


def matmul(a: Sequence[Sequence[float]], b: Sequence[Sequence[float]]) -> Matrix3:
    """Return the product of two 3x3 matrices."""
    rows = [
        (
            sum(a[i][k] * b[k][0] for k in range(3)),
            sum(a[i][k] * b[k][1] for k in range(3)),
            sum(a[i][k] * b[k][2] for k in range(3)),
        )
        for i in range(3)
    ]
    return (rows[0], rows[1], rows[2])


def position_from_translation(
    t: Sequence[float],
) -> tuple[Position, Cartesian]:
    """Return the position and cartesian coordinates of a point at OpenCV ``(x, y, z)``, mm."""
    right, down, forward = float(t[0]), float(t[1]), float(t[2])
    distance = math.sqrt(right * right + down * down + forward * forward)
    return (
        Position(distance, math.atan2(right, forward), math.atan2(-down, forward)),
        Cartesian(forward, -right, -down),
    )


def orientation_from_rotation(rotation: Sequence[Sequence[float]]) -> Orientation:
    """Return yaw, pitch and roll of a marker whose rotation in OpenCV's frame is given."""
    r = matmul(matmul(_M, rotation), transpose(_M))
    pitch = math.asin(max(-1.0, min(1.0, r[0][2])))
    yaw = math.atan2(-r[0][1], r[0][0])
    roll = math.atan2(-r[1][2], r[2][2])
    return Orientation(yaw, pitch, roll)


def rotation_from_orientation(orientation: Orientation) -> Matrix3:
    """Return the rotation in OpenCV's frame of a marker with the given orientation.

    The inverse of :func:`orientation_from_rotation` (for pitch within ±90°).
    """
    yaw, pitch, roll = orientation
    ca, sa = math.cos(roll), math.sin(roll)
    cb, sb = math.cos(pitch), math.sin(pitch)
    cc, sc = math.cos(yaw), math.sin(yaw)
    rx: Matrix3 = ((1.0, 0.0, 0.0), (0.0, ca, -sa), (0.0, sa, ca))
    ry: Matrix3 = ((cb, 0.0, sb), (0.0, 1.0, 0.0), (-sb, 0.0, cb))
    rz: Matrix3 = ((cc, -sc, 0.0), (sc, cc, 0.0), (0.0, 0.0, 1.0))
    r = matmul(matmul(rx, ry), rz)
    return matmul(matmul(transpose(_M), r), _M)
