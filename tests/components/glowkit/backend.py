"""The Glow Board's hardware backend: its line protocol over a serial port."""

from __future__ import annotations

import math
from typing import ClassVar

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports import read_line
from j5aio.components import DistanceSensorInterface
from j5aio.errors import UnexpectedReplyError, UnsupportedFirmwareError

from .boards import GlowBoard
from .light_sensor import LightSensor, LightSensorInterface

__all__ = ["GlowBackend"]

#: The firmware major versions this backend speaks.
SUPPORTED_VERSIONS = ("1",)

_LINE = read_line()


class GlowBackend(
    SerialHardwareBackend[GlowBoard], LightSensorInterface, DistanceSensorInterface,
):
    """Drives a Glow Board through its serial port."""

    board = GlowBoard

    BAUDRATE: ClassVar[int] = 57_600
    #: The USB IDs of the board's USB-serial adapter (imaginary ones).
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x1209, 0x6C0E)})

    async def _handshake(self, *, time_scale: float) -> None:
        """Ask the board who it is, check that we speak its firmware, and note its version."""
        name, _, version = (await self._ask(b"?")).partition(":")
        if name != "GLOW":
            raise UnexpectedReplyError(f"{self.port} is not a Glow Board: it says {name!r}")
        if version.split(".")[0] not in SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, SUPPORTED_VERSIONS)
        self.firmware_version = version

    async def _ask(self, command: bytes) -> str:
        """Send one command line and return the board's reply line."""
        reply = (await self.exchange(command + b"\n", _LINE)).decode("ascii", "replace")
        if reply.startswith("ERR"):
            raise UnexpectedReplyError(f"the Glow Board refused {command!r}: {reply}")
        return reply

    async def _ask_number(self, command: bytes) -> float:
        """Send one command line and return the number the board replies."""
        return self._number(command, await self._ask(command))

    @staticmethod
    def _number(command: bytes, reply: str) -> float:
        try:
            number = float(reply)
        except ValueError:
            number = math.nan
        if not math.isfinite(number) or number < 0:
            raise UnexpectedReplyError(f"expected a number after {command!r}, got {reply!r}")
        return number

    # -- light sensors ------------------------------------------------------------------

    def _check_light_sensor(self, identifier: int) -> None:
        if identifier not in range(GlowBoard.LIGHT_SENSOR_COUNT):
            raise ValueError(f"the Glow Board has light sensors 0 to 3, not {identifier!r}")

    async def get_light_sensor_lux(self, identifier: int) -> float:
        """Read the light on a sensor, in lux."""
        self._check_light_sensor(identifier)
        return await self._ask_number(b"L%d" % identifier)

    async def get_light_sensor_gain(self, identifier: int) -> int:
        """Read a sensor's gain from the board."""
        self._check_light_sensor(identifier)
        gain = await self._ask_number(b"G%d" % identifier)
        if gain not in LightSensor.GAINS:
            raise UnexpectedReplyError(f"the Glow Board reports a gain of {gain}")
        return int(gain)

    async def set_light_sensor_gain(self, identifier: int, gain: int) -> None:
        """Set a sensor's gain."""
        self._check_light_sensor(identifier)
        reply = await self._ask(b"G%d %d" % (identifier, gain))
        if reply != "OK":
            raise UnexpectedReplyError(f"expected OK after setting a gain, got {reply!r}")

    # -- the distance sensor ------------------------------------------------------------

    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        """Read the distance sensor, in millimetres; ``None`` when nothing is in range."""
        if identifier != 0:
            raise ValueError(f"the Glow Board has distance sensor 0 only, not {identifier!r}")
        reply = await self._ask(b"D")
        return None if reply == "-" else self._number(b"D", reply)
