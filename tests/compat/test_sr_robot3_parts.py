"""The parts of j5aio.compat.sr_robot3 that need no robot: numbers, units, errors, markers."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
import serial

from j5aio.compat.sr_robot3 import exceptions, raw_serial
from j5aio.compat.sr_robot3.astoria import RobotMode, robot_mode
from j5aio.compat.sr_robot3.camera import _jpeg
from j5aio.compat.sr_robot3.game_specific import marker_size_table
from j5aio.compat.sr_robot3.kch import LED, Colour
from j5aio.compat.sr_robot3.marker import Marker
from j5aio.compat.sr_robot3.motor_board import MotorStatus
from j5aio.compat.sr_robot3.power_board import PowerStatus
from j5aio.compat.sr_robot3.servo_board import ServoStatus
from j5aio.compat.sr_robot3.utils import (
    float_bounds_check,
    map_to_float,
    map_to_int,
    singular,
)
from j5aio.compat.units import volts_on_1023_scale, whole_millimetres
from j5aio.competition.metadata import Mode
from j5aio.errors import CommunicationTimeoutError
from j5aio.vision.markers import Marker as CoreMarker
from j5aio.vision.markers import Orientation, PixelCoordinates, Position


def test_singular_takes_the_one_board() -> None:
    assert singular({"A": 1}) == 1
    with pytest.raises(RuntimeError, match="No boards of this type found"):
        singular({})
    with pytest.raises(RuntimeError, match="expected only one to be connected, but found 2"):
        singular({"A": 1, "B": 2})


def test_numbers_are_checked_and_mapped_as_sr_robot3_does() -> None:
    assert float_bounds_check("0.5", 0, 1, "no") == 0.5
    with pytest.raises(TypeError, match=r"^no$"):
        float_bounds_check(None, 0, 1, "no")
    with pytest.raises(ValueError, match=r"^no$"):
        float_bounds_check(2, 0, 1, "no")
    assert map_to_int(-0.1234, -1, 1, -1000, 1000) == -123  # truncated towards zero
    assert map_to_float(512, 0, 1023, 0.0, 5.0) == 2.502


@pytest.mark.parametrize("adc", [0, 1, 511, 512, 1000, 1023])
def test_volts_are_sr_robot3s_for_every_adc_value(adc: int) -> None:
    j5aio_volts = adc / 1024 * 5  # (what j5aio's SR Arduino codec gives)
    assert volts_on_1023_scale(j5aio_volts) == round(adc / 1023 * 5, 3)


@pytest.mark.parametrize("millimetres", [1, 29, 123, 500, 4000, 10344])
def test_ultrasound_millimetres_are_the_firmwares(millimetres: int) -> None:
    assert whole_millimetres(millimetres / 1000) == millimetres  # (j5aio's metres)
    assert whole_millimetres(None) == 0


def test_status_answers_are_read_as_sr_robot3_reads_them() -> None:
    power = PowerStatus.from_status_response("0,1,0,0,0,0,0:31:1:5012:x")
    assert power == PowerStatus((False, True, False, False, False, False, False), 31, True,
                                5.012, ["x"])
    assert MotorStatus.from_status_response("0,1:12000") == MotorStatus((False, True), 12.0)
    assert ServoStatus.from_status_response("1:0") == ServoStatus(True, False)


def test_the_errors_keep_sr_robot3s_bases_and_messages() -> None:
    assert issubclass(exceptions.MetadataKeyError, KeyError)
    assert str(exceptions.MetadataKeyError("zone")) == "Key 'zone' not present in metadata"
    assert issubclass(exceptions.MetadataNotReadyError, RuntimeError)
    wrong = exceptions.IncorrectBoardError("MCv4B", "PBv4B")
    assert isinstance(wrong, OSError)
    assert str(wrong) == "Board returned type 'MCv4B', expected 'PBv4B'"
    error = exceptions.disconnected(CommunicationTimeoutError("the board did not answer"))
    assert isinstance(error, exceptions.BoardDisconnectionError)
    assert isinstance(error, OSError) and str(error) == "the board did not answer"


def test_after_game_over_a_board_error_ends_the_program_quietly(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture,
) -> None:
    monkeypatch.setattr(exceptions, "_game_over", type(exceptions._game_over)())
    caplog.set_level("INFO", logger="sr.robot3.timeout")
    exceptions.end_of_match()
    assert "Timeout expired: Game Over!" in caplog.text
    ending = exceptions.disconnected(CommunicationTimeoutError("closed"))
    assert isinstance(ending, SystemExit) and ending.code == 0


def test_robot_modes() -> None:
    assert robot_mode(Mode.COMP) is RobotMode.COMP
    assert robot_mode(Mode.DEV) is RobotMode.DEV


def test_the_game_marker_sizes() -> None:
    table = marker_size_table()
    assert (table[0], table[49], table[50], table[99], table[100], table[199]) == (
        150, 150, 200, 200, 80, 80)
    assert 200 not in table


def test_a_picture_is_saved_as_jpeg_unless_named_otherwise() -> None:
    assert _jpeg("seen") == Path("seen.jpg")
    assert _jpeg(Path("a/seen.png")) == Path("a/seen.png")


def test_markers_have_sr_robot3s_units() -> None:
    corners = tuple(PixelCoordinates(x, y) for x, y in ((1, 2), (3, 2), (3, 4), (1, 4)))
    core = CoreMarker(
        7, 150.0, PixelCoordinates(2.0, 3.0), corners,  # type: ignore[arg-type]
        position=Position(1234.9, 0.1, -0.2), orientation=Orientation(0.3, 0.2, 0.1),
    )
    marker = Marker.from_j5aio_marker(core)
    assert marker.id == 7 and marker.size == 150 and isinstance(marker.size, int)
    assert marker.position.distance == 1234  # whole mm, as sr-robot3's int()
    assert marker.position[1:] == (0.1, -0.2)
    assert marker.orientation == (0.3, 0.2, 0.1)
    assert marker.pixel_centre == (2.0, 3.0) and marker.pixel_corners[2] == (3, 4)
    assert repr(marker) == ("<Marker id=7 distance=1234mm horizontal_angle=0.10rad "
                            "vertical_angle=-0.20rad size=150mm>")
    no_pose = CoreMarker(7, 150.0, PixelCoordinates(2.0, 3.0), corners)  # type: ignore[arg-type]
    assert math.isnan(no_pose.position.distance)
    with pytest.raises(ValueError, match="Marker lacks pose information"):
        Marker.from_j5aio_marker(no_pose)


def test_the_stand_in_leds_do_nothing_but_check_colours() -> None:
    led = LED()
    led.r = True
    led.g = True
    led.b = True
    led.colour = Colour.WHITE
    assert (led.r, led.g, led.b, led.colour) == (False, False, False, (False, False, False))
    with pytest.raises(ValueError, match="3 values"):
        led.colour = (True,)  # type: ignore[assignment]


@pytest.fixture
def no_boot_delay(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(raw_serial, "sleep", lambda seconds: None)


class FakePort:
    def __init__(self, device: str, serial_number: str) -> None:
        self.device = device
        self.serial_number = serial_number
        self.manufacturer = "Team"
        self.product = "Gadget"
        self.vid = 0x2341
        self.pid = 0x0043


@pytest.mark.usefixtures("no_boot_delay")
def test_raw_serial_devices_are_found_by_serial_number_and_talked_to(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    ports = [FakePort("loop://", "X1"), FakePort("loop://", "X2"), FakePort("/no/such", "X3")]
    monkeypatch.setattr("serial.tools.list_ports.comports", lambda: ports)
    found = raw_serial.RawSerial._get_supported_boards([("X1", 9600), ("X3", 9600)])
    assert list(found) == ["X1", "X3"]  # (X3's port cannot be opened: it is retried on use)
    device = found["X1"]
    assert device.identify() == ("Team", "Gadget", "X1", "2341:0043")
    assert device.get_board_type() == "RawSerial"
    device.write(b"hello\nworld")
    assert device.read_until() == b"hello\n"
    assert device.read(5) == b"world"
    assert device.port.baudrate == 9600
    assert repr(device).startswith("<RawSerial: ")
    with pytest.raises(exceptions.BoardDisconnectionError, match="could not be established"):
        found["X3"].write(b"x")


@pytest.mark.usefixtures("no_boot_delay")
def test_a_raw_serial_device_that_fails_mid_transfer(monkeypatch: pytest.MonkeyPatch) -> None:
    device = raw_serial.RawSerial("loop://")

    def broken(*args: Any) -> bytes:
        raise serial.SerialException("gone")

    monkeypatch.setattr(device.port, "read", broken)
    with pytest.raises(exceptions.BoardDisconnectionError, match="disconnected during"):
        device.read(1)
    assert not device.port.is_open
    monkeypatch.undo()
    device.write(b"back")  # (the port is opened again on the next use)
    assert device.read(4) == b"back"


def test_a_raw_serial_device_that_will_not_open_is_skipped(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture,
) -> None:
    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise ValueError("bad port")

    monkeypatch.setattr("serial.serial_for_url", refuse)
    monkeypatch.setattr("serial.tools.list_ports.comports", lambda: [FakePort("x", "X1")])
    assert dict(raw_serial.RawSerial._get_supported_boards([("X1", 9600)])) == {}
    assert "Failed to connect to X1 because: bad port" in caplog.text


class StubCamera:
    """Stands in for j5aio's marker camera: one marker of the game, one of another."""

    marker_sizes = {3: 80.0}
    calibration = None

    def see(self) -> list[CoreMarker]:
        from j5aio.vision.sizes import UnknownMarkerError

        raise UnknownMarkerError("marker 600 has no size")

    def capture(self) -> str:
        return "a picture"


def test_markers_the_game_has_no_size_for_are_left_out(monkeypatch: pytest.MonkeyPatch) -> None:
    import j5aio.vision.detect as detect
    from j5aio.compat.sr_robot3.camera import AprilCamera

    corners = tuple(PixelCoordinates(x, y) for x, y in ((1, 2), (3, 2), (3, 4), (1, 4)))
    asked: list[dict[int, float]] = []

    def markers(frame: str, calibration: None, sizes: dict[int, float]) -> list[CoreMarker]:
        assert frame == "a picture"
        asked.append(dict(sizes))
        return [
            CoreMarker(marker, sizes[marker], PixelCoordinates(2.0, 3.0),
                       corners, position=Position(900.0, 0.0, 0.0),  # type: ignore[arg-type]
                       orientation=Orientation(0.0, 0.0, 0.0))
            for marker in (3, 600)
        ]

    monkeypatch.setattr(detect, "detect_marker_ids", lambda frame: [3, 600])
    monkeypatch.setattr(detect, "detect_markers", markers)
    camera = AprilCamera(StubCamera(), "stub")  # type: ignore[arg-type]
    assert [marker.id for marker in camera.see()] == [3]
    assert asked == [{3: 80.0, 600: 1.0}]  # (600 measured as anything, then dropped)
    assert [marker.size for marker in camera.see(frame="a picture")] == [80]
