import struct
from typing import Any

import pytest
import usb.core

from j5aio.backends.hardware.sr.v4 import SRV4ServoBoardHardwareBackend
from j5aio.boards.sr.v4 import ServoBoard
from j5aio.errors import (
    CommunicationError,
    NotSupportedByHardwareError,
    UnsupportedFirmwareError,
)
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator

Backend = SRV4ServoBoardHardwareBackend


async def test_handshake_inits_once_and_centres_every_servo() -> None:
    sim = SRServoBoardFw2Simulator("SB1")
    board = await Backend.from_usb_device(sim)
    assert isinstance(board, ServoBoard)
    assert board.firmware_version == "2"
    assert sim.init_requests == 1
    assert sim.initialised
    assert sim.positions == (0,) * 12
    await board.setup()
    assert sim.init_requests == 1
    await board.close()


@pytest.mark.parametrize(
    ("position", "wire"), [(1.0, 100), (-1.0, -100), (0.5, 50), (0.005, 0), (0.015, 2)]
)
async def test_positions_are_rounded_half_to_even(position: float, wire: int) -> None:
    sim = SRServoBoardFw2Simulator("SB1")
    board = await Backend.from_usb_device(sim)
    assert isinstance(board, ServoBoard)
    await board.servos[7].set_position(position)
    assert sim.positions[7] == wire
    assert await board.servos[7].get_position() == position
    await board.close()


async def test_servo_errors_send_nothing() -> None:
    sim = SRServoBoardFw2Simulator("SB1")
    board = await Backend.from_usb_device(sim)
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(NotSupportedByHardwareError, match="cannot unpower"):
        await backend.set_servo_position(0, None)
    with pytest.raises(ValueError, match="servos 0 to 11"):
        await backend.set_servo_position(12, 0.0)
    with pytest.raises(ValueError, match="servos 0 to 11"):
        await backend.get_servo_position(True)
    with pytest.raises(ValueError, match="between -1 and 1"):
        await backend.set_servo_position(0, 1.5)
    assert sim.positions == (0,) * 12
    assert await backend.get_servo_position(0) == 0.0
    await board.close()


async def test_no_12v_supply_suggests_checking_the_power() -> None:
    sim = SRServoBoardFw2Simulator("SB1", has_12v=False)
    with pytest.raises(CommunicationError, match="12 V"):
        await Backend.from_usb_device(sim)


class StandIn:
    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0011  # noqa: N815
    serial_number = "SB2"

    def __init__(self, *, version: int = 2, error: usb.core.USBError | None = None) -> None:
        self.version = version
        self.error = error

    def ctrl_transfer(
        self,
        request_type: int,
        request: int,
        value: int = 0,
        index: int = 0,
        data: Any = None,
        timeout: int | None = None,
    ) -> Any:
        if self.error is not None:
            raise self.error
        if request_type == 0x80:
            return struct.pack("<I", self.version)
        return len(data)


@pytest.mark.parametrize("errno", [5, 110])
async def test_handshake_io_errors_suggest_the_12v_supply(errno: int) -> None:
    device = StandIn(error=usb.core.USBError("boom", errno=errno))
    with pytest.raises(CommunicationError, match="12 V") as info:
        await Backend.from_usb_device(device)
    assert info.value.errno == errno  # type: ignore[attr-defined]


async def test_handshake_stall_points_at_the_firmware() -> None:
    device = StandIn(error=usb.core.USBError("Pipe error", errno=32))
    with pytest.raises(CommunicationError, match="firmware other than version 2"):
        await Backend.from_usb_device(device)


async def test_unsupported_firmware() -> None:
    with pytest.raises(UnsupportedFirmwareError, match="'3'"):
        await Backend.from_usb_device(StandIn(version=3))


def test_make_safe_now_leaves_the_servos_where_they_are() -> None:
    assert SRV4ServoBoardHardwareBackend.make_safe_now(object(), 0.5) is False  # type: ignore[arg-type]
