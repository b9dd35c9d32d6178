"""The pure parts of vision: axes, marker sizes, calibrations (no optional libraries)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from j5aio.vision import (
    KNOWN_CALIBRATIONS,
    CameraCalibration,
    Marker,
    MarkerSizes,
    Orientation,
    PixelCoordinates,
    UnknownMarkerError,
    known_calibration,
)
from j5aio.vision.geometry import (
    matmul,
    orientation_from_rotation,
    position_from_translation,
    rotation_from_orientation,
    transpose,
)

# -- axes ----------------------------------------------------------------------------


def test_a_point_right_and_below_is_positive_right_and_negative_up() -> None:
    # OpenCV: x right, y down, z forward
    position, cartesian = position_from_translation((100.0, 50.0, 1000.0))
    assert position.distance == pytest.approx(math.sqrt(100**2 + 50**2 + 1000**2))
    assert position.horizontal_angle == pytest.approx(math.atan2(100, 1000))
    assert position.horizontal_angle > 0
    assert position.vertical_angle == pytest.approx(math.atan2(-50, 1000))
    assert position.vertical_angle < 0
    # student: x forward, y left, z up
    assert cartesian == pytest.approx((1000.0, -100.0, -50.0))


def test_a_marker_facing_the_camera_squarely_has_zero_orientation() -> None:
    identity = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    assert orientation_from_rotation(identity) == pytest.approx((0.0, 0.0, 0.0))


@pytest.mark.parametrize(
    "angles",
    [(0.3, 0.0, 0.0), (0.0, 0.4, 0.0), (0.0, 0.0, -0.7), (0.5, -0.3, 1.2), (-1.0, 0.8, 3.0)],
)
def test_orientation_round_trips_through_the_rotation(angles: tuple[float, float, float]) -> None:
    rotation = rotation_from_orientation(Orientation(*angles))
    assert orientation_from_rotation(rotation) == pytest.approx(angles)
    # it is a rotation
    product = matmul(rotation, transpose(rotation))
    for i in range(3):
        for j in range(3):
            assert product[i][j] == pytest.approx(1.0 if i == j else 0.0, abs=1e-12)


def test_yaw_turns_about_the_vertical_axis_and_roll_about_the_line_of_sight() -> None:
    yawed = rotation_from_orientation(Orientation(0.5, 0.0, 0.0))
    # OpenCV's y axis (down) is unchanged by a yaw
    assert [yawed[i][1] for i in range(3)] == pytest.approx([0.0, 1.0, 0.0])
    rolled = rotation_from_orientation(Orientation(0.0, 0.0, 0.5))
    # OpenCV's z axis (the line of sight) is unchanged by a roll
    assert [rolled[i][2] for i in range(3)] == pytest.approx([0.0, 0.0, 1.0])


def test_marker_without_pose_says_so() -> None:
    pixel = PixelCoordinates(10.0, 20.0)
    marker = Marker(4, 150.0, pixel, (pixel, pixel, pixel, pixel))
    assert not marker.has_pose
    assert math.isnan(marker.distance)
    assert "no pose" in str(marker)
    position, cartesian = position_from_translation((0.0, 0.0, 1000.0))
    posed = marker._replace(position=position, cartesian=cartesian)
    assert posed.has_pose
    assert posed.distance == 1000.0
    assert "1000 mm away" in str(posed)


# -- marker sizes --------------------------------------------------------------------


def test_marker_sizes_give_sizes_and_name_a_missing_id() -> None:
    sizes = MarkerSizes({0: 150, 1: 150, 2: 150, 7: 200})
    sizes = sizes | MarkerSizes.of_range(range(100, 104), 80)
    assert sizes.size_of(7) == 200.0
    assert sizes.size_of(101) == 80.0
    assert len(sizes) == 8
    assert sorted(sizes) == [0, 1, 2, 7, 100, 101, 102, 103]
    assert sizes[0] == 150.0
    with pytest.raises(UnknownMarkerError, match=r"marker 55 .*ids 0-2, 7, 100-103"):
        sizes.size_of(55)
    assert "default=None" in repr(sizes)


def test_marker_sizes_default_covers_other_ids() -> None:
    sizes = MarkerSizes({1: 100}, default=150)
    assert sizes.size_of(300) == 150.0
    assert sizes.default == 150.0
    merged = MarkerSizes({2: 50}) | sizes
    assert merged.default == 150.0
    assert (sizes | {3: 30}).default == 150.0
    with pytest.raises(UnknownMarkerError, match="no id"):
        MarkerSizes().size_of(1)


@pytest.mark.parametrize(
    ("table", "error", "message"),
    [
        ({"1": 150}, TypeError, "marker id must be an int"),
        ({True: 150}, TypeError, "marker id must be an int"),
        ({587: 150}, ValueError, "not in AprilTag 36h11"),
        ({1: "150"}, TypeError, "must be a number"),
        ({1: 0}, ValueError, "more than 0"),
        ({1: math.inf}, ValueError, "more than 0"),
    ],
)
def test_bad_marker_sizes_are_refused(table: dict, error: type, message: str) -> None:  # type: ignore[type-arg]
    with pytest.raises(error, match=message):
        MarkerSizes(table)


# -- calibrations --------------------------------------------------------------------


def test_calibration_checks_its_values() -> None:
    with pytest.raises(ValueError, match="fx"):
        CameraCalibration(0, 900, 320, 240)
    with pytest.raises(TypeError, match="fy"):
        CameraCalibration(900, "900", 320, 240)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="cx"):
        CameraCalibration(900, 900, -1, 240)
    with pytest.raises(TypeError, match="cy"):
        CameraCalibration(900, 900, 1, None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="coefficients"):
        CameraCalibration(900, 900, 320, 240, (0.1, 0.2))
    with pytest.raises(TypeError, match="finite"):
        CameraCalibration(900, 900, 320, 240, (0.1, 0.2, 0.0, math.nan))


def test_calibration_scales_to_the_same_aspect_ratio_only() -> None:
    c270 = KNOWN_CALIBRATIONS["Logitech C270"]
    half = c270.scaled_to(640, 480)
    assert half.fx == pytest.approx(c270.fx / 2)
    assert half.cx == pytest.approx((c270.cx + 0.5) / 2 - 0.5)
    assert half.resolution == (640, 480)
    assert known_calibration("Logitech C270", 640, 480) == half
    with pytest.raises(ValueError, match="aspect ratio"):
        c270.scaled_to(1280, 720)
    with pytest.raises(ValueError, match="does not say its resolution"):
        CameraCalibration(900, 900, 320, 240).scaled_to(640, 480)
    with pytest.raises(ValueError, match="known cameras: Logitech C270, Logitech C500"):
        known_calibration("Webcam 3000", 640, 480)


OPENCV_XML = """<?xml version="1.0"?>
<opencv_storage>
<cameraResolution>
  640 480</cameraResolution>
<cameraMatrix type_id="opencv-matrix">
  <rows>3</rows>
  <cols>3</cols>
  <dt>d</dt>
  <data>
    600. 0. 321.
    0. 601. 242.
    0. 0. 1.</data></cameraMatrix>
<dist_coeffs type_id="opencv-matrix">
  <rows>1</rows>
  <cols>5</cols>
  <dt>d</dt>
  <data>
    0.1 -0.2 0.001 0.002 0.3</data></dist_coeffs>
</opencv_storage>
"""


def test_calibration_loads_an_opencv_file(tmp_path: Path) -> None:
    path = tmp_path / "camera.xml"
    path.write_text(OPENCV_XML)
    calibration = CameraCalibration.from_file(path)
    assert calibration == CameraCalibration(
        600, 601, 321, 242, (0.1, -0.2, 0.001, 0.002, 0.3), (640, 480)
    )
    bare = tmp_path / "bare.xml"
    bare.write_text(
        "<opencv_storage><cameraMatrix><data>5 0 1 0 6 2 0 0 1</data></cameraMatrix>"
        "</opencv_storage>"
    )
    assert CameraCalibration.from_file(bare) == CameraCalibration(5, 6, 1, 2)


def test_calibration_round_trips_through_json(tmp_path: Path) -> None:
    original = KNOWN_CALIBRATIONS["Logitech C500"]
    path = tmp_path / "c500.json"
    path.write_text(original.to_json())
    assert CameraCalibration.from_file(path) == original
    plain = CameraCalibration(900, 900, 639.5, 359.5)
    path.write_text(plain.to_json())
    assert CameraCalibration.from_file(path) == plain
    assert "resolution" not in json.loads(plain.to_json())


@pytest.mark.parametrize(
    "text",
    [
        "<opencv_storage></opencv_storage>",
        "<opencv_storage><cameraMatrix><data>1 2 3</data></cameraMatrix></opencv_storage>",
        "<not xml",
        '{"fx": 1}',
    ],
)
def test_a_file_that_is_not_a_calibration_is_refused(tmp_path: Path, text: str) -> None:
    path = tmp_path / "bad.xml"
    path.write_text(text)
    with pytest.raises(ValueError, match="not a camera calibration"):
        CameraCalibration.from_file(path)
