"""j5's import paths work inside j5aio, giving the very objects of their new homes."""

from __future__ import annotations

import importlib

import pytest

from j5aio import errors, robot
from j5aio.backends.backend import BackendMeta
from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor


@pytest.mark.parametrize(
    ("module", "name", "home"),
    [
        ("j5aio.components", "NotSupportedByComponentError", errors.NotSupportedByComponentError),
        ("j5aio.components.derived", "UltrasoundSensor", UltrasoundSensor),
        ("j5aio.components.derived", "UltrasoundInterface", UltrasoundInterface),
        ("j5aio.backends.backend", "CommunicationError", errors.CommunicationError),
        ("j5aio.base_robot", "BaseRobot", robot.BaseRobot),
        ("j5aio.backends", "BackendMeta", BackendMeta),
        ("j5aio.backends.hardware", "NotSupportedByHardwareError",
         errors.NotSupportedByHardwareError),
    ],
)
def test_the_old_path_gives_the_new_home(module: str, name: str, home: object) -> None:
    assert getattr(importlib.import_module(module), name) is home
