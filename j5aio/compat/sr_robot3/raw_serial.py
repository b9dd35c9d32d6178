"""sr-robot3's raw serial devices: ports found by USB serial number, read and written as bytes.

These are a team's own devices (an Arduino with its own firmware, say), so j5aio has no
board for them: the port is opened with pyserial, as sr-robot3 does.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from time import sleep
from types import MappingProxyType
from typing import Any, NamedTuple

from j5aio.compat.sr_robot3.exceptions import BoardDisconnectionError
from j5aio.compat.sr_robot3.utils import BoardIdentity

__all__ = ["DEFAULT_BAUDRATE", "RawSerial", "RawSerialDevice"]

LOGGER = logging.getLogger("sr.robot3.raw_serial")
DEFAULT_BAUDRATE = 115200


class RawSerialDevice(NamedTuple):
    """A serial device to look for by its USB serial number."""

    serial_number: str
    baudrate: int = DEFAULT_BAUDRATE


class RawSerial:
    """A serial port opened for the program to use as it likes.

    :param serial_port: the port's path or URL.
    :param baudrate: its baud rate.
    :param identity: who the device is, from its USB descriptor.
    """

    __slots__ = ("_identity", "_serial", "delay_after_connect")

    def __init__(
        self,
        serial_port: str,
        baudrate: int = DEFAULT_BAUDRATE,
        identity: BoardIdentity | None = None,
    ) -> None:
        from serial import serial_for_url

        self._identity = identity if identity is not None else BoardIdentity()
        self._serial = serial_for_url(
            serial_port, baudrate=baudrate, timeout=0.5, do_not_open=True)
        self.delay_after_connect = 2.0  # (many boards reset when the port opens)
        self._reconnect()

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``RawSerial`` (unused: the device is the team's own)."""
        return "RawSerial"

    @classmethod
    def _get_supported_boards(
        cls, serial_devices: list[tuple[str, int]],
    ) -> MappingProxyType[str, RawSerial]:
        """Open the ports whose USB serial numbers are in ``serial_devices``."""
        from serial.tools.list_ports import comports

        wanted = {
            device.serial_number: device
            for device in (RawSerialDevice(number, rate) for number, rate in serial_devices)
        }
        boards: dict[str, RawSerial] = {}
        for port in comports():
            found = wanted.get(port.serial_number or "")
            if found is None:
                continue
            identity = BoardIdentity(
                port.manufacturer or "", port.product or "", port.serial_number or "",
                f"{port.vid or 0:04x}:{port.pid or 0:04x}",
            )
            try:
                boards[identity.asset_tag] = cls(port.device, found.baudrate, identity)
            except Exception as error:  # (as sr-robot3: one bad device does not stop the robot)
                LOGGER.warning(f"Failed to connect to {found.serial_number} because: {error}")
        return MappingProxyType(boards)

    def identify(self) -> BoardIdentity:
        """The device's identity, from its USB descriptor."""
        return self._identity

    @property
    def port(self) -> Any:
        """The pyserial port object."""
        return self._serial

    def write(self, data: bytes) -> None:
        """Send ``data``."""
        with self._reconnecting():
            self._serial.write(data)

    def read(self, size: int) -> bytes:
        """Read up to ``size`` bytes (fewer after the 0.5 s timeout)."""
        with self._reconnecting():
            data: bytes = self._serial.read(size)
            return data

    def read_until(self, terminator: bytes = b"\n") -> bytes:
        """Read up to and including ``terminator`` (or what came before the timeout)."""
        with self._reconnecting():
            data: bytes = self._serial.read_until(terminator)
            return data

    @contextmanager
    def _reconnecting(self) -> Iterator[None]:
        from serial import SerialException

        name = f"{self._identity.board_type}:{self._identity.asset_tag}"
        if not self._serial.is_open and not self._reconnect():
            raise BoardDisconnectionError(f"Connection to port {name} could not be established")
        try:
            yield
        except (SerialException, OSError):
            self._serial.close()
            LOGGER.warning(f"Port {name} disconnected")
            raise BoardDisconnectionError(f"Port {name} disconnected during transaction") from None

    def _reconnect(self) -> bool:
        from serial import SerialException

        name = f"{self._identity.board_type}:{self._identity.asset_tag}"
        try:
            self._serial.open()
            sleep(self.delay_after_connect)
            self._serial.reset_input_buffer()
        except SerialException:
            LOGGER.error(f"Failed to connect to port {name}")
            return False
        LOGGER.info(f"Connected to port {name}")
        return True

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._serial}>"
