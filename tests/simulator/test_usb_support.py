from __future__ import annotations

import array
import errno

import pytest
import usb.core

from j5aio.simulator.usb_support import (
    DFU_RUNTIME_INTERFACE,
    SimulatedConfiguration,
    SimulatedInterface,
    as_payload,
    no_device_error,
    pipe_error,
    timeout_error,
)
from tests.dataclass_twins import assert_like_generated


def test_pipe_error_is_what_pyusb_raises_on_a_stall() -> None:
    error = pipe_error()
    assert isinstance(error, usb.core.USBError)
    assert error.errno == errno.EPIPE == 32
    assert error.backend_error_code == -9
    assert error.strerror == "Pipe error"


def test_no_device_error() -> None:
    error = no_device_error()
    assert isinstance(error, usb.core.USBError)
    assert error.errno == errno.ENODEV == 19
    assert error.backend_error_code == -4
    assert error.strerror.startswith("No such device")


def test_timeout_error() -> None:
    error = timeout_error()
    assert isinstance(error, usb.core.USBTimeoutError)
    assert error.errno == errno.ETIMEDOUT == 110
    assert error.backend_error_code == -7


@pytest.mark.parametrize(
    ("data", "expected"),
    [
        (None, b""),
        (3, b"\x00\x00\x00"),
        ("hi", b"hi"),
        (b"\x01\x02", b"\x01\x02"),
        (bytearray(b"\x05"), b"\x05"),
        ([1, 2, 255], b"\x01\x02\xff"),
        (array.array("B", [9, 8]), b"\x09\x08"),
    ],
)
def test_as_payload_converts_like_pyusb(data: object, expected: bytes) -> None:
    assert as_payload(data) == expected  # type: ignore[arg-type]


def test_configuration_stand_in() -> None:
    config = SimulatedConfiguration(1, (DFU_RUNTIME_INTERFACE,))
    assert config.bNumInterfaces == 1
    assert config.interfaces() == (DFU_RUNTIME_INTERFACE,)
    assert list(config) == [DFU_RUNTIME_INTERFACE]
    assert config[(0, 0)].bInterfaceClass == 0xFE
    assert config[(0, 0)].bInterfaceSubClass == 0x01
    with pytest.raises(IndexError):
        config[(1, 0)]


def test_the_stand_ins_are_the_generated_dataclasses() -> None:
    assert_like_generated(
        SimulatedInterface,
        [((0, 0, 0xFE, 1, 1), {}), ((1, 0, 0xFF, 0, 0), {"bNumEndpoints": 2})],
    )
    other = SimulatedInterface(1, 0, 0xFF, 0, 0)
    assert_like_generated(
        SimulatedConfiguration,
        [((1, (DFU_RUNTIME_INTERFACE,)), {}), ((1, (DFU_RUNTIME_INTERFACE, other)), {})],
    )
