"""Every public name of sr-robot3 2026.0.3 is in j5aio.compat.sr_robot3, with its signature.

The peer's surface is read from sr-robot3 itself, in this Python (``tox -e peers``
installs it) or in the Python named by ``J5AIO_SR_ROBOT3_PYTHON``; without either the
test is skipped and says so.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import pytest

from .api_surface import surface

SURFACE = Path(__file__).resolve().parent / "api_surface.py"

#: The classes a program reaches through Robot (not in sr-robot3's __all__), by module.
REACHED = [
    "robot:Robot",
    "power_board:PowerBoard", "power_board:Outputs", "power_board:Output",
    "power_board:BatterySensor", "power_board:Piezo", "power_board:Led",
    "power_board:PowerStatus", "power_board:PowerOutputPosition",
    "motor_board:MotorBoard", "motor_board:Motor", "motor_board:MotorStatus",
    "motor_board:MotorPower",
    "servo_board:ServoBoard", "servo_board:Servo", "servo_board:ServoStatus",
    "arduino:Arduino", "arduino:Pin", "arduino:GPIOPinMode", "arduino:AnalogPins",
    "kch:KCH", "kch:LED", "kch:UserLED", "kch:Colour",
    "camera:AprilCamera",
    "marker:Marker", "marker:Position", "marker:Orientation", "marker:PixelCoordinates",
    "marker:Coordinates",
    "raw_serial:RawSerial", "raw_serial:RawSerialDevice",
    "utils:BoardIdentity",
    "astoria:RobotMode",
    "exceptions:IncorrectBoardError",
]

#: Members of sr-robot3's classes that j5aio leaves out, and why.
LEFT_OUT: dict[str, set[str]] = {
    # How a board is found and made: j5aio's KitRobot finds the boards.
    "power_board:PowerBoard": {"__init__"},
    "motor_board:MotorBoard": {"__init__"},
    "servo_board:ServoBoard": {"__init__"},
    "arduino:Arduino": {"__init__"},
    "kch:KCH": {"__init__"},
    "power_board:Outputs": {"__init__"},
    "power_board:Output": {"__init__"},
    "power_board:Led": {"__init__"},
    "power_board:BatterySensor": {"__init__"},
    "power_board:Piezo": {"__init__"},
    "motor_board:Motor": {"__init__"},
    "servo_board:Servo": {"__init__"},
    "arduino:Pin": {"__init__"},
    # AprilCamera is made from an april_vision frame source; here from j5aio's camera.
    "camera:AprilCamera": {"__init__", "from_id", "from_webots_camera"},
    # (april_vision's marker): j5aio's markers are made from j5aio's.
    "marker:Marker": {"from_april_vision_marker"},
}


def peer_surface() -> dict[str, Any]:
    if find_spec("sr") is not None and find_spec("sr.robot3") is not None:
        python = sys.executable
    else:
        python = os.environ.get("J5AIO_SR_ROBOT3_PYTHON", "")
        if not python:
            pytest.skip(
                "sr-robot3 is not installed: run `tox -e peers` (it installs sr-robot3 "
                "2026.0.3), or name a Python that has it in J5AIO_SR_ROBOT3_PYTHON"
            )
    result = subprocess.run(
        [python, str(SURFACE), "sr.robot3", *REACHED],
        capture_output=True, text=True, timeout=120, check=True,
        env={**os.environ, "PYTHONPATH": ""}, cwd=SURFACE.parent.parent,
    )
    found: dict[str, Any] = json.loads(result.stdout)
    return found


@pytest.fixture(scope="module")
def peer() -> dict[str, Any]:
    return peer_surface()


@pytest.fixture(scope="module")
def ours() -> dict[str, Any]:
    return surface("j5aio.compat.sr_robot3", REACHED)


def test_every_name_in_sr_robot3s_all_is_here(peer: dict[str, Any], ours: dict[str, Any]) -> None:
    import j5aio.compat.sr_robot3 as compat

    names = [name for name in peer if ":" not in name]
    assert sorted(compat.__all__) == sorted(names)
    for name in names:
        if peer[name]["kind"] == "class":
            continue  # (compared member by member below)
        assert ours[name] == peer[name], name


@pytest.mark.parametrize("reference", [*REACHED, "Colour", "Note", "RawSerialDevice"])
def test_each_class_has_sr_robot3s_members_and_signatures(
    reference: str, peer: dict[str, Any], ours: dict[str, Any],
) -> None:
    theirs, mine = peer[reference], ours[reference]
    assert mine["kind"] == theirs["kind"], reference
    assert mine["bases"] == theirs["bases"], reference  # so `except` clauses still catch
    if theirs["kind"] == "enum":
        assert mine["members"] == theirs["members"]
        return
    assert mine["fields"] == theirs["fields"]
    left_out = LEFT_OUT.get(reference, set())
    for name, member in theirs["members"].items():
        if name in left_out:
            continue
        assert name in mine["members"], f"{reference}.{name} is missing"
        assert mine["members"][name] == member, f"{reference}.{name}"
