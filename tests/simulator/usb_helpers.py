"""Helpers for driving a simulated USB board the way an SR backend does."""

from __future__ import annotations

import array
import struct

from j5aio.simulator.base import UsbBoardSimulator

READ = 0x80
WRITE = 0x00
REQUEST = 64


def read(device: UsbBoardSimulator, index: int, length: int) -> bytes:
    """Do an SR read request; return the bytes the board sent."""
    reply = device.ctrl_transfer(READ, REQUEST, 0, index, length)
    assert isinstance(reply, array.array)
    return reply.tobytes()


def read_u32(device: UsbBoardSimulator, index: int) -> int:
    """Do a 4-byte SR read request; return the little-endian value."""
    value: int = struct.unpack("<I", read(device, index, 4))[0]
    return value


def write(device: UsbBoardSimulator, index: int, value: int = 0, data: bytes | None = None) -> int:
    """Do an SR write request; return what ctrl_transfer returns."""
    written = device.ctrl_transfer(WRITE, REQUEST, value, index, data)
    assert isinstance(written, int)
    return written
