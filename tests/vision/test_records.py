"""The vision package's records behave as the frozen dataclasses they stand in for."""

from __future__ import annotations

import copy
import pickle
from dataclasses import FrozenInstanceError

import pytest

from j5aio.simulator.camera import DEFAULT_CALIBRATION, SimulatedCamera
from j5aio.vision.arena_map import WallMarker
from j5aio.vision.calibration import CameraCalibration


def test_a_wall_marker_checks_and_keeps_its_fields_as_numbers() -> None:
    marker = WallMarker(3, 1, 2, 0)
    assert marker == WallMarker(3, 1.0, 2.0, 0.0, 150.0, 250.0)
    assert hash(marker) == hash(WallMarker(3, 1.0, 2.0, 0.0))
    assert marker != WallMarker(4, 1, 2, 0)
    assert repr(marker) == "WallMarker(id=3, x=1.0, y=2.0, facing=0.0, size=150.0, z=250.0)"
    assert pickle.loads(pickle.dumps(marker)) == marker
    assert copy.deepcopy(marker) is marker
    with pytest.raises(FrozenInstanceError):
        marker.x = 5.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="size"):
        WallMarker(3, 1, 2, 0, size=0)


def test_a_calibration_is_equal_shown_and_frozen_as_before() -> None:
    calibration = CameraCalibration(100, 100, 50, 40, [0, 0, 0, 0], [100.0, 80.0])  # type: ignore[arg-type]
    assert calibration == CameraCalibration(100.0, 100.0, 50.0, 40.0, (0.0,) * 4, (100, 80))
    assert calibration.resolution == (100, 80) and calibration.distortion == (0.0,) * 4
    assert repr(calibration) == (
        "CameraCalibration(fx=100.0, fy=100.0, cx=50.0, cy=40.0, "
        "distortion=(0.0, 0.0, 0.0, 0.0), resolution=(100, 80))"
    )
    assert len({calibration, CameraCalibration(100, 100, 50, 40, (0, 0, 0, 0), (100, 80))}) == 1
    assert pickle.loads(pickle.dumps(calibration)) == calibration
    with pytest.raises(FrozenInstanceError):
        calibration.fx = 1.0  # type: ignore[misc]


def test_the_simulated_camera_is_a_record_of_the_simulated_camera_module() -> None:
    camera = SimulatedCamera(resolution=(640, 360))
    assert camera == SimulatedCamera(DEFAULT_CALIBRATION, (640, 360), None)
    assert camera != SimulatedCamera()
    assert type(camera).__module__ == "j5aio.simulator.camera"
    assert repr(camera).startswith("SimulatedCamera(calibration=CameraCalibration(fx=1387.5")
    assert pickle.loads(pickle.dumps(camera)) == camera
    with pytest.raises(FrozenInstanceError):
        camera.resolution = None  # type: ignore[misc]
