"""detect_markers on rendered pictures: accuracy, no false ids, conventions, input checks."""

from __future__ import annotations

import math
import random

import pytest

np = pytest.importorskip("numpy")
cv2 = pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")

from j5aio.simulator.camera import DEFAULT_CALIBRATION  # noqa: E402
from j5aio.vision import (  # noqa: E402
    CameraCalibration,
    MarkerDetector,
    MarkerSizes,
    Orientation,
    UnknownMarkerError,
    detect_marker_ids,
    detect_markers,
)
from j5aio.vision.detect import AMBIGUITY_RATIO, PoseCandidate, choose_pose  # noqa: E402
from j5aio.vision.geometry import position_from_translation, rotation_from_orientation  # noqa: E402
from j5aio.vision.render import Lighting, MarkerItem, QuadItem, render  # noqa: E402

RESOLUTION = (1280, 720)
SIZES = MarkerSizes.of_range(range(0, 587), 150)


def marker_at(
    marker_id: int, distance: float, bearing_deg: float, yaw: float, pitch: float, roll: float,
    *, height: float = 0.0, size: float = 150.0,
) -> MarkerItem:
    bearing = math.radians(bearing_deg)
    centre = (distance * math.sin(bearing), height, distance * math.cos(bearing))
    rotation = rotation_from_orientation(
        Orientation(math.radians(yaw), math.radians(pitch), math.radians(roll))
    )
    return MarkerItem(marker_id, size, centre, rotation)


#: bearing, yaw, pitch, roll and elevation (degrees) of the marker at every distance:
#: face-on, turned either way (the planar-pose ambiguity is at its worst for a turned
#: marker far away), tilted, rolled, upside down, above and below the camera.
ORIENTATIONS = (
    (0, 0, 0, 0, 0),
    (12, 30, 0, 0, 0),
    (-10, -35, 15, 0, 0),
    (5, 0, -20, 20, 0),
    (-15, 20, 10, -90, 0),
    (8, -25, 0, 180, 0),
    (3, 45, 0, 0, 3),
    (-5, 0, 30, 0, -3),
    (-8, -45, 0, 0, 0),
    (10, 40, 0, 90, -2),
)
DISTANCES = (500, 750, 1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500, 5000)
POSES = [(distance, *orientation) for distance in DISTANCES for orientation in ORIENTATIONS]


def accuracy_errors(
    distance: float, bearing: float, yaw: float, pitch: float, roll: float, elevation: float
) -> tuple[list[int], float, float, float, float]:
    """Ids found, and errors: distance (fraction), bearing, elevation, orientation (deg)."""
    height = -distance * math.tan(math.radians(elevation))  # OpenCV's y is down
    item = marker_at(42, distance, bearing, yaw, pitch, roll, height=height)
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [item])
    markers = detect_markers(image, DEFAULT_CALIBRATION, SIZES)
    ids = [m.id for m in markers]
    if ids != [42]:
        return ids, math.inf, math.inf, math.inf, math.inf
    marker = markers[0]
    truth, cartesian = position_from_translation(item.centre)
    assert marker.size == 150.0
    assert marker.cartesian == pytest.approx(cartesian, rel=0.03, abs=20)
    expected = (math.radians(yaw), math.radians(pitch), math.radians(roll))
    orientation = max(
        math.degrees(abs(math.remainder(got - want, math.tau)))
        for got, want in zip(marker.orientation, expected, strict=True)
    )
    return (
        ids,
        abs(marker.position.distance - truth.distance) / truth.distance,
        math.degrees(abs(marker.position.horizontal_angle - truth.horizontal_angle)),
        math.degrees(abs(marker.position.vertical_angle - truth.vertical_angle)),
        orientation,
    )


@pytest.mark.parametrize("distance", DISTANCES)
def test_accuracy_on_rendered_150mm_markers_from_half_a_metre_to_five(distance: float) -> None:
    # Every pose of the grid at this distance must meet every bound:
    # distance within 3 %, bearing within 1.5 deg, orientation within 5 deg, no false id.
    failures = []
    for orientation in ORIENTATIONS:
        ids, d, bearing, elevation, angle = accuracy_errors(distance, *orientation)
        if ids != [42] or d >= 0.03 or bearing >= 1.5 or elevation >= 1.5 or angle >= 5.0:
            failures.append((orientation, ids, d, bearing, elevation, angle))
    assert failures == []


def candidate(error: float, normal_down: float, name: str) -> PoseCandidate:
    return PoseCandidate(error, normal_down, name, None)


def test_the_pose_that_fits_clearly_better_is_chosen_whatever_its_tilt() -> None:
    fits = candidate(0.05, 0.4, "fits")
    mirror = candidate(0.05 * AMBIGUITY_RATIO + 0.01, 0.0, "mirror")
    assert choose_pose([mirror, fits]) is fits
    assert choose_pose([fits]) is fits


def test_when_the_fit_cannot_tell_the_nearer_vertical_face_is_chosen() -> None:
    tilted = candidate(0.050, -0.3, "tilted")
    upright = candidate(0.055, 0.02, "upright")
    assert choose_pose([tilted, upright]) is upright
    # both tiny: equal fits, whatever their ratio
    assert choose_pose([candidate(1e-5, 0.3, "a"), candidate(1e-3, -0.1, "b")]).rvec == "b"
    # a tie on both counts keeps the better fit
    first, second = candidate(0.05, 0.1, "first"), candidate(0.051, -0.1, "second")
    assert choose_pose([second, first]) is first


def test_choosing_from_no_pose_is_an_error() -> None:
    with pytest.raises(ValueError, match="at least one pose"):
        choose_pose([])


def test_corners_symmetric_about_the_principal_row_still_give_the_pose() -> None:
    # OpenCV 4.14's IPPE misses these corners by ~60 px (both its poses); SQPnP is asked.
    camera = np.array([[1387.5, 0, 639.5], [0, 1387.5, 359.5], [0, 0, 1]], dtype=np.float64)
    half = 75.0
    corners3d = np.array(
        [[-half, half, 0], [half, half, 0], [half, -half, 0], [-half, -half, 0]], dtype=np.float64
    )
    pixels = np.array(
        [[863.71411133, 329.26593018], [805.71411133, 329.69189453],
         [805.71411133, 389.30810547], [863.71411133, 389.73406982]],
        dtype=np.float64,
    )
    detector = MarkerDetector()
    rvec, tvec = detector._solve_pose(corners3d, pixels, camera, np.zeros(0))
    projected, _ = cv2.projectPoints(corners3d, rvec, tvec, camera, np.zeros(0))
    assert np.abs(projected.reshape(-1, 2) - pixels).max() < 0.2
    position, _ = position_from_translation(tvec.ravel().tolist())
    assert position.distance == pytest.approx(3500, rel=0.01)


def test_rendered_edges_sit_where_the_camera_would_see_them() -> None:
    # A camera pixel sums the light on its area, so along a row through the marker's black
    # border, the dark width left of a pixel boundary is exactly how far the square's left
    # edge is from it. (One texture sample a pixel put it up to 0.06 px out: as much as the
    # perspective that tells a far marker's pose from its mirror image.)
    calibration = DEFAULT_CALIBRATION
    errors = []
    for distance in (3000.0, 3700.0, 4100.0, 4600.0, 5000.0):
        for offset in (0.0, 13.7, 27.1, 41.3):
            item = MarkerItem(0, 150.0, (offset, 0.0, distance), rotation_from_orientation(
                Orientation(0.0, 0.0, 0.0)))
            image = render(calibration, RESOLUTION, [item], background=(255, 255, 255))
            width = calibration.fx * 150.0 / distance
            centre = calibration.fx * offset / distance + calibration.cx
            row = round(calibration.cy - width / 2 + width / 16)  # in the top black cell
            boundary = math.floor(centre)  # columns before it end at boundary - 0.5
            dark = ((255.0 - image[row, :boundary, 0].astype(np.float64)) / 255.0).sum()
            errors.append(abs((boundary - 0.5 - (centre - width / 2)) - dark))
    assert max(errors) < 0.02


def test_pixel_centre_is_the_projected_centre() -> None:
    item = marker_at(3, 1200, 10, 40, 0, 0)
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [item])
    (marker,) = detect_markers(image, DEFAULT_CALIBRATION, SIZES)
    x, y, z = item.centre
    c = DEFAULT_CALIBRATION
    assert marker.pixel_centre.x == pytest.approx(c.fx * x / z + c.cx, abs=0.3)
    assert marker.pixel_centre.y == pytest.approx(c.fy * y / z + c.cy, abs=0.3)
    # not the mean of the corners, which perspective pulls towards the near side
    mean_x = sum(p.x for p in marker.pixel_corners) / 4
    assert abs(mean_x - marker.pixel_centre.x) > 0.3
    # the first corner is the marker's bottom left
    first = marker.pixel_corners[0]
    assert first.x < marker.pixel_centre.x and first.y > marker.pixel_centre.y


def test_no_false_ids_in_busy_noisy_scenes() -> None:
    rng = random.Random(7)
    wanted_total = 0
    for scene in range(6):
        ids = rng.sample(range(587), 6)
        items: list[QuadItem | MarkerItem] = []
        for k, marker_id in enumerate(ids):
            bearing = -18 + 7 * k
            items.append(
                marker_at(marker_id, rng.uniform(1200, 3500), bearing, rng.uniform(-30, 30), 0, 0,
                          height=rng.uniform(-150, 150))
            )
        lighting = Lighting(brightness=0.8, gradient=0.3, blur=0.6, noise=4.0, seed=scene)
        image = render(DEFAULT_CALIBRATION, RESOLUTION, items, lighting=lighting)
        found = [m.id for m in detect_markers(image, DEFAULT_CALIBRATION, SIZES)]
        assert set(found) <= set(ids), "a marker id was reported that is not in the picture"
        assert sorted(found) == sorted(ids)
        wanted_total += len(ids)
    assert wanted_total == 36


def test_random_noise_holds_no_markers() -> None:
    rng = np.random.default_rng(3)
    for _ in range(5):
        image = rng.integers(0, 256, (720, 1280), dtype=np.uint8)
        assert detect_marker_ids(image) == []


def test_greyscale_bgr_and_bgra_pictures_give_the_same_markers() -> None:
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [marker_at(9, 1000, 0, 10, 0, 0)])
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    bgra = cv2.cvtColor(image, cv2.COLOR_BGR2BGRA)
    results = [
        detect_markers(picture, DEFAULT_CALIBRATION, SIZES)
        for picture in (image, grey, bgra, grey[:, :, None])
    ]
    assert all(r == results[0] for r in results)
    assert detect_marker_ids(image) == [9]


def test_without_a_calibration_ids_and_pixels_are_still_found() -> None:
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [marker_at(5, 1500, 5, 0, 0, 0),
                                                     marker_at(2, 1000, -8, 0, 0, 0)])
    markers = detect_markers(image, None, {2: 150, 5: 150})
    assert [m.id for m in markers] == [2, 5]
    assert all(not m.has_pose and math.isnan(m.cartesian.x) for m in markers)
    assert all(0 < m.pixel_centre.x < 1280 for m in markers)


def test_distortion_is_taken_into_account() -> None:
    # A picture rendered by a perfect pinhole, then distorted as a real lens would.
    calibration = CameraCalibration(900, 900, 639.5, 359.5, (-0.2, 0.05, 0.0, 0.0, 0.0))
    pinhole = CameraCalibration(900, 900, 639.5, 359.5)
    item = marker_at(11, 1500, 18, 0, 0, 0)
    ideal = render(pinhole, RESOLUTION, [item])
    camera = np.array([[900, 0, 639.5], [0, 900, 359.5], [0, 0, 1]], dtype=np.float64)
    # each pixel of the distorted picture shows what the ideal one has where it undistorts to
    ys, xs = np.mgrid[0:720, 0:1280].astype(np.float32)
    grid = np.stack([xs.ravel(), ys.ravel()], axis=1).reshape(-1, 1, 2)
    ideal_points = cv2.undistortPoints(
        grid, camera, np.array(calibration.distortion), P=camera
    ).reshape(720, 1280, 2)
    distorted = cv2.remap(ideal, ideal_points[:, :, 0], ideal_points[:, :, 1], cv2.INTER_LINEAR)
    (with_model,) = detect_markers(distorted, calibration, SIZES)
    (without,) = detect_markers(distorted, pinhole, SIZES)
    truth, _ = position_from_translation(item.centre)
    error_with = abs(with_model.position.horizontal_angle - truth.horizontal_angle)
    error_without = abs(without.position.horizontal_angle - truth.horizontal_angle)
    assert math.degrees(error_with) < 0.3
    assert error_with < error_without


def test_an_id_with_no_size_is_a_clear_error() -> None:
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [marker_at(77, 1000, 0, 0, 0, 0)])
    with pytest.raises(UnknownMarkerError, match="marker 77 was seen"):
        detect_markers(image, DEFAULT_CALIBRATION, {1: 150})
    with pytest.raises(TypeError, match="marker_sizes must be"):
        detect_markers(image, DEFAULT_CALIBRATION, [150])  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("image", "error", "message"),
    [
        ([[0, 1]], TypeError, "numpy array"),
        (np.zeros((4, 4), dtype=np.float32), TypeError, "uint8"),
        (np.zeros((4, 4, 2), dtype=np.uint8), ValueError, "shape"),
        (np.zeros((4,), dtype=np.uint8), ValueError, "shape"),
    ],
)
def test_bad_pictures_are_refused(image: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        detect_markers(image, None, SIZES)  # type: ignore[arg-type]


def test_detector_settings_are_checked() -> None:
    with pytest.raises(ValueError, match="quad_decimate"):
        MarkerDetector(quad_decimate=0.5)
    with pytest.raises(ValueError, match="max_hamming"):
        MarkerDetector(max_hamming=2)
    full = MarkerDetector(quad_decimate=1.0, threads=1, max_hamming=1)
    image = render(DEFAULT_CALIBRATION, RESOLUTION, [marker_at(1, 5000, 0, 0, 0, 0)])
    assert full.detect_ids(image) == [1]
