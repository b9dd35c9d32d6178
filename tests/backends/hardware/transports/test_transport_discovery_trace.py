"""Tests of port discovery, USB device discovery and the wire loggers."""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import usb.core

from j5aio.backends.hardware.transports import (
    TRACE,
    PortInfo,
    find_port,
    find_usb_devices,
    list_serial_ports,
    match_ports,
    wire_logger,
)
from j5aio.backends.hardware.transports.discovery import ComPortLike, libusb_help
from j5aio.errors import CommunicationError, USBCommunicationError


@dataclass
class FakeComPort:
    device: str
    vid: int | None = None
    pid: int | None = None
    serial_number: str | None = None
    manufacturer: str | None = None
    product: str | None = None
    description: str = "n/a"


PORTS = [
    FakeComPort("/dev/ttyACM1", 0x1BDA, 0x0011, "SRB2", "Student Robotics", "Power board v4"),
    FakeComPort("/dev/ttyACM0", 0x1BDA, 0x0011, "SRA1", "Student Robotics", "Power board v4"),
    FakeComPort("/dev/ttyUSB0", 0x0403, 0x6001, "sr123", "Student Robotics", "MCV4B"),
    FakeComPort("/dev/ttyUSB1", 0x0403, 0x6001, "A1", "FTDI", "FT232R USB UART"),
    FakeComPort("/dev/ttyS0"),
]


def source() -> Iterable[ComPortLike]:
    return PORTS


def test_list_serial_ports_makes_typed_records() -> None:
    ports = list_serial_ports(source)
    assert ports[2] == PortInfo(
        device="/dev/ttyUSB0",
        vid=0x0403,
        pid=0x6001,
        serial_number="sr123",
        manufacturer="Student Robotics",
        product="MCV4B",
        description="n/a",
    )
    assert ports[2].is_ftdi
    assert not ports[0].is_ftdi
    assert ports[4].vid is None


def test_list_serial_ports_from_pyserial_returns_port_infos() -> None:
    assert all(isinstance(port, PortInfo) for port in list_serial_ports())


def test_list_serial_ports_wraps_os_errors() -> None:
    def broken() -> Iterable[ComPortLike]:
        raise OSError("sysfs unavailable")

    with pytest.raises(CommunicationError, match="sysfs unavailable"):
        list_serial_ports(broken)


def test_match_ports_by_id_and_strings_in_serial_order() -> None:
    ports = list_serial_ports(source)
    power = match_ports(ports, {(0x1BDA, 0x0011)})
    assert [p.serial_number for p in power] == ["SRA1", "SRB2"]
    motor = match_ports(ports, {(0x0403, 0x6001)}, manufacturer="Student Robotics", product="MCV4B")
    assert [p.device for p in motor] == ["/dev/ttyUSB0"]
    assert match_ports(ports, {(0x0403, 0x6001)}, product="nothing") == []
    assert match_ports(ports, set()) == []


def test_find_port_resolves_symlinks(tmp_path: Path) -> None:
    target = tmp_path / "ttyACM0"
    target.touch()
    link = tmp_path / "by-id-power"
    link.symlink_to(target)
    ports = [FakeComPort(str(target), 0x1BDA, 0x0011)]
    found = find_port(str(link), lambda: ports)
    assert found is not None and found.device == str(target)
    assert find_port(os.fspath(tmp_path / "other"), lambda: ports) is None


class FakeDevice:
    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0010  # noqa: N815
    serial_number = "SRXYZ"

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        raise NotImplementedError


def test_find_usb_devices_uses_the_finder() -> None:
    calls: list[dict[str, Any]] = []
    device = FakeDevice()

    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        calls.append({"find_all": find_all, "vid": idVendor, "pid": idProduct})
        return iter([device])

    assert find_usb_devices(0x1BDA, 0x0010, finder=finder) == [device]
    assert calls == [{"find_all": True, "vid": 0x1BDA, "pid": 0x0010}]


def test_find_usb_devices_explains_a_missing_libusb(monkeypatch: pytest.MonkeyPatch) -> None:
    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        raise usb.core.NoBackendError("No backend available")

    monkeypatch.setattr("ctypes.util.find_library", lambda name: None)
    with pytest.raises(CommunicationError, match="libusb") as caught:
        find_usb_devices(1, 2, finder=finder)
    assert "apt install libusb-1.0-0" in str(caught.value)


def test_find_usb_devices_explains_a_libusb_it_cannot_use(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        raise usb.core.NoBackendError("No backend available")

    monkeypatch.setattr("ctypes.util.find_library", lambda name: "libusb-1.0.so.0")
    with pytest.raises(CommunicationError) as caught:
        find_usb_devices(1, 2, finder=finder)
    message = str(caught.value)
    assert message.startswith("libusb is installed (libusb-1.0.so.0), but pyusb could not use it")
    assert "apt install" not in message
    assert "PYUSB_DEBUG=debug" in message


def test_libusb_help_tries_both_library_names() -> None:
    asked: list[str] = []

    def only_the_windows_name(name: str) -> str | None:
        asked.append(name)
        return "C:\\libusb-1.0.dll" if name == "libusb-1.0" else None

    assert "libusb is installed (C:\\libusb-1.0.dll)" in libusb_help(only_the_windows_name)
    assert asked == ["usb-1.0", "libusb-1.0"]
    assert "Install libusb" in libusb_help(lambda name: None)


def test_find_usb_devices_wraps_usb_errors() -> None:
    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        raise usb.core.USBError("Access denied", errno=13)

    with pytest.raises(USBCommunicationError, match="1bda:0010") as caught:
        find_usb_devices(0x1BDA, 0x0010, finder=finder)
    assert caught.value.errno == 13


def test_find_usb_devices_with_pyusb(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: dict[str, Any] = {}

    def fake_find(**kwargs: Any) -> Any:
        seen.update(kwargs)
        return []

    monkeypatch.setattr(usb.core, "find", fake_find)
    assert find_usb_devices(0x1BDA, 0x0010) == []
    assert seen == {"find_all": True, "idVendor": 0x1BDA, "idProduct": 0x0010}


def test_trace_level_is_registered() -> None:
    assert TRACE == 5
    assert logging.getLevelName(TRACE) == "TRACE"


def test_wire_logger_names_one_logger_per_port() -> None:
    assert wire_logger("/dev/ttyACM0").name == "j5aio.wire./dev/ttyACM0"
    assert wire_logger("socket://127.0.0.1:9000").name == "j5aio.wire.socket://127_0_0_1:9000"


def test_find_usb_devices_lets_other_errors_through() -> None:
    # A finder's own failure (not pyusb's) is not dressed up as a USB error.
    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        raise LookupError("the finder's own fault")

    with pytest.raises(LookupError, match="the finder's own fault"):
        find_usb_devices(0x1BDA, 0x0010, finder=finder)
