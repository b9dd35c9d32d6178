"""Drawing the markers found onto a picture, and writing pictures to files."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from j5aio.vision._optional import require

if TYPE_CHECKING:
    from j5aio.vision.image import Image
    from j5aio.vision.markers import Marker

__all__ = ["annotate", "write_image"]


def annotate(image: Image, markers: Sequence[Marker]) -> Image:
    """Return a BGR copy of ``image`` with each marker outlined and labelled.

    The outline is green, the first corner red, and the label gives the id and, with a
    calibration, the distance in mm.
    """
    np, cv2 = require("numpy"), require("cv2")
    out = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()
    scale = max(0.4, out.shape[1] / 1600)
    thickness = max(1, round(out.shape[1] / 640))
    for marker in markers:
        corners = np.array([[c.x, c.y] for c in marker.pixel_corners], dtype=np.float64)
        points = np.round(corners * 16).astype(np.int32)
        cv2.polylines(out, [points], True, (0, 200, 0), thickness, cv2.LINE_AA, shift=4)
        first = (round(corners[0][0]), round(corners[0][1]))
        cv2.circle(out, first, thickness + 2, (0, 0, 255), -1, cv2.LINE_AA)
        label = f"{marker.id}"
        if not math.isnan(marker.position.distance):
            label += f" {marker.position.distance:.0f}mm"
        origin = (round(marker.pixel_centre.x), round(float(corners[:, 1].min()) - 4))
        cv2.putText(out, label, origin, cv2.FONT_HERSHEY_SIMPLEX, scale, (0, 0, 0),
                    thickness + 2, cv2.LINE_AA)
        cv2.putText(out, label, origin, cv2.FONT_HERSHEY_SIMPLEX, scale, (0, 255, 255),
                    thickness, cv2.LINE_AA)
    return out


def write_image(path: Path, image: Image) -> None:
    """Write ``image`` to ``path`` in the format its suffix names.

    :raises OSError: OpenCV could not write the file.
    """
    cv2 = require("cv2")
    if not cv2.imwrite(str(path), image):
        raise OSError(f"could not write the picture to {path}")
