"""Camera calibrations: the pinhole model (focal lengths, centre, distortion) of a camera.

A calibration turns pixels into distances and angles. Without one a camera still finds
markers and their pixels, but not how far away they are.

Calibrations of the webcams the kits ship are built in (:data:`KNOWN_CALIBRATIONS`); any
other comes from a file (:meth:`CameraCalibration.from_file`): an OpenCV calibration file
(the XML that OpenCV's calibration tools write, with ``cameraMatrix``, ``dist_coeffs`` and
``cameraResolution``) or a JSON file with the fields of :class:`CameraCalibration`.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Final

from j5aio.components._checks import check_number

__all__ = ["KNOWN_CALIBRATIONS", "CameraCalibration", "known_calibration"]


def _pixels(name: str, value: object, low: float) -> float:
    return check_number(
        value, name=name, low=low, high=sys.float_info.max, allowed="a finite number of pixels"
        + (", more than 0" if low > 0 else ", 0 or more"),
    )


@dataclass(frozen=True)
class CameraCalibration:
    """The pinhole model of one camera at one resolution.

    :param fx: focal length along x, pixels.
    :param fy: focal length along y, pixels.
    :param cx: x of the principal point (the optical centre), pixels.
    :param cy: y of the principal point, pixels.
    :param distortion: OpenCV's distortion coefficients ``(k1, k2, p1, p2[, k3...])``;
        empty for a camera without distortion.
    :param resolution: the ``(width, height)`` the calibration was made at, if known.
    :raises TypeError: a value is not a number.
    :raises ValueError: a focal length is not more than 0, the principal point is
        negative, or there are not 0, 4, 5, 8, 12 or 14 distortion coefficients.
    """

    fx: float
    fy: float
    cx: float
    cy: float
    distortion: tuple[float, ...] = field(default=())
    resolution: tuple[int, int] | None = None

    def __post_init__(self) -> None:
        for name in ("fx", "fy", "cx", "cy"):
            low = sys.float_info.min if name.startswith("f") else 0.0
            object.__setattr__(self, name, _pixels(name, getattr(self, name), low))
        coefficients = tuple(self.distortion)
        if len(coefficients) not in (0, 4, 5, 8, 12, 14):
            raise ValueError(
                "distortion must have 0, 4, 5, 8, 12 or 14 coefficients (OpenCV's models), "
                f"not {len(coefficients)}",
            )
        for c in coefficients:
            if isinstance(c, bool) or not isinstance(c, int | float) or not math.isfinite(c):
                raise TypeError(f"distortion coefficients must be finite numbers, not {c!r}")
        object.__setattr__(self, "distortion", tuple(float(c) for c in coefficients))
        if self.resolution is not None:
            width, height = self.resolution
            object.__setattr__(self, "resolution", (int(width), int(height)))

    def scaled_to(self, width: int, height: int) -> CameraCalibration:
        """Return this calibration for the same camera at another resolution.

        Valid where the camera scales its whole sensor to that resolution, i.e. at the
        same aspect ratio.

        :raises ValueError: the calibration has no resolution, or the aspect ratio differs.
        """
        if self.resolution is None:
            raise ValueError("this calibration does not say its resolution: it cannot be scaled")
        w0, h0 = self.resolution
        if width * h0 != height * w0:
            raise ValueError(
                f"cannot scale a {w0}x{h0} calibration to {width}x{height}: the aspect "
                "ratio differs (the camera crops instead of scaling). Calibrate the camera "
                "at that resolution.",
            )
        s = width / w0
        # Pixel centres sit at integer coordinates: scale about the corner of the picture.
        return CameraCalibration(
            self.fx * s,
            self.fy * s,
            (self.cx + 0.5) * s - 0.5,
            (self.cy + 0.5) * s - 0.5,
            self.distortion,
            (width, height),
        )

    @classmethod
    def from_file(cls, path: str | Path) -> CameraCalibration:
        """Read a calibration from an OpenCV XML calibration file or a JSON file.

        :raises ValueError: the file is not a calibration this can read.
        :raises OSError: the file cannot be read.
        """
        from xml.etree.ElementTree import ParseError  # (here: few programs read one)

        path = Path(path)
        text = path.read_text(encoding="utf-8")
        try:
            if text.lstrip().startswith("{"):
                return cls._from_json(text)
            return cls._from_opencv_xml(text)
        except (KeyError, IndexError, ValueError, TypeError, ParseError) as exc:
            raise ValueError(f"{path} is not a camera calibration this can read: {exc}") from exc

    @classmethod
    def _from_json(cls, text: str) -> CameraCalibration:
        import json  # (here: the simulated camera, made at every start, reads no file)

        data = json.loads(text)
        resolution = data.get("resolution")
        return cls(
            data["fx"],
            data["fy"],
            data["cx"],
            data["cy"],
            tuple(data.get("distortion", ())),
            None if resolution is None else (resolution[0], resolution[1]),
        )

    @classmethod
    def _from_opencv_xml(cls, text: str) -> CameraCalibration:
        import xml.etree.ElementTree as ET

        root = ET.fromstring(text)

        def numbers(tag: str) -> list[float]:
            node = root.find(tag)
            if node is None:
                raise KeyError(f"no <{tag}>")
            data = node.find("data")
            return [float(v) for v in (data if data is not None else node).text.split()]  # type: ignore[union-attr]

        matrix = numbers("cameraMatrix")
        if len(matrix) != 9:
            raise ValueError(f"cameraMatrix has {len(matrix)} numbers, not 9")
        distortion = tuple(numbers("dist_coeffs")) if root.find("dist_coeffs") is not None else ()
        resolution = None
        if root.find("cameraResolution") is not None:
            w, h = numbers("cameraResolution")
            resolution = (int(w), int(h))
        return cls(matrix[0], matrix[4], matrix[2], matrix[5], distortion, resolution)

    def to_json(self) -> str:
        """Return the calibration as JSON that :meth:`from_file` reads back."""
        data: dict[str, object] = {
            "fx": self.fx,
            "fy": self.fy,
            "cx": self.cx,
            "cy": self.cy,
            "distortion": list(self.distortion),
        }
        if self.resolution is not None:
            data["resolution"] = list(self.resolution)
        import json

        return json.dumps(data, indent=2)


#: Calibrations of webcams that the kits ship, keyed by camera name, each at the
#: resolution it was measured at. Published calibration data (the april_vision project's
#: calibration files, measured in November 2022): the Logitech C270 (USB 046d:0825) at
#: 1280x960 and the Logitech C500 (as its business twin the B500, USB 046d:0807) at
#: 1280x1024. :func:`known_calibration` scales them to other resolutions of the same
#: aspect ratio.
KNOWN_CALIBRATIONS: Final[dict[str, CameraCalibration]] = {
    "Logitech C270": CameraCalibration(
        1387.52826,
        1387.64512,
        681.279056,
        532.635142,
        (0.01737599, 0.36629486, -0.00773113, 0.00315102, -1.34355748),
        (1280, 960),
    ),
    "Logitech C500": CameraCalibration(
        1057.11133,
        1066.61029,
        602.433099,
        451.876692,
        (-0.0930654, 0.30046762, -0.00657921, -0.00055965, -0.48481949),
        (1280, 1024),
    ),
}

#: USB vendor:product ids of the known cameras, to recognise them when they are plugged in.
KNOWN_USB_IDS: Final[dict[str, str]] = {
    "046d:0825": "Logitech C270",
    "046d:0807": "Logitech C500",
}


def known_calibration(camera: str, width: int, height: int) -> CameraCalibration:
    """Return the built-in calibration of ``camera`` at ``width`` x ``height``.

    :raises ValueError: the camera is not known, or not at that aspect ratio.
    """
    try:
        base = KNOWN_CALIBRATIONS[camera]
    except KeyError:
        known = ", ".join(sorted(KNOWN_CALIBRATIONS))
        raise ValueError(
            f"no built-in calibration for {camera!r}; known cameras: {known}. Calibrate the "
            "camera and load the file with CameraCalibration.from_file().",
        ) from None
    return base.scaled_to(width, height)
