from __future__ import annotations

import array
import errno
from typing import Any, ClassVar

import pytest
import usb.core

from j5aio.simulator.base import SerialBoardSimulator, SimulatorUnpluggedError, UsbBoardSimulator
from j5aio.simulator.usb_support import UsbStall


class EchoBoard(SerialBoardSimulator):
    """Echoes bytes back in upper case; prints a banner at boot."""

    baudrate: ClassVar[int] = 9600
    boot_delay: ClassVar[float] = 0.5
    resets_on_open: ClassVar[bool] = True
    powered_by_usb: ClassVar[bool] = True

    def __init__(self) -> None:
        super().__init__("E1", usb_vid=1, usb_pid=2, manufacturer="M", product=None)
        self.boots = 0

    def _boot(self) -> bytes:
        self.boots += 1
        return b"hello\n"

    def _process(self, data: bytes) -> bytes:
        return data.upper()


class QuietBoard(EchoBoard):
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = False


class LoopbackDevice(UsbBoardSimulator):
    idVendor: ClassVar[int] = 0x1234  # noqa: N815
    idProduct: ClassVar[int] = 0x5678  # noqa: N815
    bcdDevice: ClassVar[int] = 0x0100  # noqa: N815

    def __init__(self) -> None:
        super().__init__("L1", manufacturer="Maker", product="Loop")
        self.last_out: tuple[int, int, int, int, bytes] | None = None

    def _control_in(
        self, request_type: int, request: int, value: int, index: int, length: int
    ) -> bytes:
        if request == 0:
            raise UsbStall()
        return bytes([request_type, request, value & 0xFF, index & 0xFF, length & 0xFF, 6, 7])

    def _control_out(
        self, request_type: int, request: int, value: int, index: int, data: bytes
    ) -> None:
        if request == 0:
            raise UsbStall()
        self.last_out = (request_type, request, value, index, data)


def test_serial_board_that_resets_on_open() -> None:
    board = EchoBoard()
    assert board.serial_number == "E1"
    assert (board.usb_vid, board.usb_pid, board.manufacturer, board.product) == (1, 2, "M", None)
    assert board.connected
    assert board.open() == b"hello\n"
    assert board.receive(b"abc") == b"ABC"
    assert board.reset() == b"hello\n"
    assert board.boots == 2


def test_serial_board_that_does_not_reset_on_open() -> None:
    board = QuietBoard()
    assert board.open() == b""
    assert board.boots == 0


def test_unplugged_serial_board_refuses_traffic() -> None:
    board = EchoBoard()
    board.unplug()
    assert not board.connected
    with pytest.raises(SimulatorUnpluggedError) as raised:
        board.receive(b"x")
    assert raised.value.errno == errno.ENODEV
    assert isinstance(raised.value, OSError)
    with pytest.raises(SimulatorUnpluggedError):
        board.open()


def test_plugging_boots_a_usb_powered_board_only() -> None:
    powered = EchoBoard()
    powered.unplug()
    powered.plug()
    assert powered.connected
    assert powered.boots == 1
    powered.plug()  # already plugged: nothing happens
    assert powered.boots == 1
    separate = QuietBoard()
    separate.unplug()
    separate.plug()
    assert separate.boots == 0


def read(device: UsbBoardSimulator, *args: Any) -> list[int]:
    reply = device.ctrl_transfer(0x80, *args)
    assert isinstance(reply, array.array)
    assert reply.typecode == "B"
    return reply.tolist()


def test_usb_in_transfer_returns_an_array_cut_to_wlength() -> None:
    device = LoopbackDevice()
    assert read(device, 5, 1, 2, 4) == [0x80, 5, 1, 2]
    assert read(device, 5, 1, 2, 64) == [0x80, 5, 1, 2, 64, 6, 7]
    assert read(device, 5) == []
    assert read(device, 5, 0, 0, [0, 0, 0]) == [0x80, 5, 0]


def test_usb_in_transfer_fills_a_given_array() -> None:
    device = LoopbackDevice()
    buffer = array.array("B", bytes(3))
    assert device.ctrl_transfer(0x80, 9, 0, 0, buffer) == 3
    assert buffer.tolist() == [0x80, 9, 0]


def test_usb_setup_fields_are_truncated_like_ctypes() -> None:
    device = LoopbackDevice()
    assert device.ctrl_transfer(0x100, 0x101, -100, 0x1_0002, 0) == 0
    assert device.last_out == (0x00, 0x01, 0xFF9C, 0x0002, b"")


def test_usb_out_transfer_returns_bytes_written() -> None:
    device = LoopbackDevice()
    assert device.ctrl_transfer(0x00, 1, 2, 3, b"abcd") == 4
    assert device.last_out == (0, 1, 2, 3, b"abcd")


def test_usb_stall_becomes_a_pipe_error() -> None:
    device = LoopbackDevice()
    with pytest.raises(usb.core.USBError) as raised:
        device.ctrl_transfer(0x80, 0, 0, 0, 4)
    assert raised.value.errno == 32
    with pytest.raises(usb.core.USBError) as raised:
        device.ctrl_transfer(0x00, 0)
    assert raised.value.errno == 32


def test_usb_device_descriptors_and_configuration() -> None:
    device = LoopbackDevice()
    assert (device.idVendor, device.idProduct, device.bcdDevice) == (0x1234, 0x5678, 0x0100)
    assert (device.manufacturer, device.product, device.serial_number) == ("Maker", "Loop", "L1")
    assert device.bNumConfigurations == 1
    config = device.get_active_configuration()
    assert len(config.interfaces()) == 1
    assert device.configurations() == (config,)
    assert list(device) == [config]
    assert device[0] is config
    assert config.bConfigurationValue == 1
    device.set_configuration()


def test_unplugged_usb_device_raises_enodev() -> None:
    device = LoopbackDevice()
    assert device.serial_number == "L1"  # read (and cached) while plugged in
    device.unplug()
    assert not device.connected
    for call in (
        lambda: device.ctrl_transfer(0x80, 1, 0, 0, 1),
        lambda: device.ctrl_transfer(0x00, 1),
        device.get_active_configuration,
        device.set_configuration,
        lambda: device.product,
    ):
        with pytest.raises(usb.core.USBError) as raised:
            call()
        assert raised.value.errno == errno.ENODEV
    assert device.serial_number == "L1"  # pyusb keeps the cached string
    device.plug()
    assert device.connected
    assert device.product == "Loop"


def test_listeners_hear_of_each_input_and_reboot_until_stopped() -> None:
    from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator

    board = SRMotorBoardFw3Simulator("LISTEN")
    heard: list[int] = []
    stop = board.listen(lambda: heard.append(len(heard)))
    board.receive(b"\x02\xc0")  # motor 0 forwards
    board.reset()
    assert heard == [0, 1]
    stop()
    stop()  # twice is harmless
    board.receive(b"\x02\x80")
    assert heard == [0, 1]
