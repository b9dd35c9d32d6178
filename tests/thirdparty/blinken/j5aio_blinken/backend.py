"""The hardware backend of the Blinken board, over a serial port."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.components.led import LEDInterface
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError
from j5aio_blinken.board import BlinkenBoard

__all__ = ["BlinkenHardwareBackend"]

_LINE = read_line()
SUPPORTED_VERSIONS = ("1",)


class BlinkenHardwareBackend(LEDInterface, SerialHardwareBackend):
    """Drives a Blinken board over its text protocol."""

    board = BlinkenBoard
    BAUDRATE: ClassVar[int] = 115_200
    #: pid.codes' test vendor and product IDs.
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x1209, 0x0001)})

    async def _handshake(self, *, time_scale: float) -> None:
        # End whatever partial line is in the board's buffer (other kinds' identification
        # probes may have left bytes there), and drop the board's answer to it.
        await self._send(b"\n")
        await self._link.drain()
        reply = (await self._exchange(b"V\n", _LINE)).decode("ascii", errors="replace")
        model, _, version = reply.partition(":")
        if model != "BLINKEN":
            raise UnexpectedReplyError(f"{self.port} answered {reply!r}, not BLINKEN:<version>")
        if version not in SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, SUPPORTED_VERSIONS)
        self._firmware_version = version

    async def _command(self, request: str) -> str:
        reply = (await self._exchange(request.encode() + b"\n", _LINE)).decode(errors="replace")
        if reply.startswith("ERR"):
            raise CommunicationError(
                f"{self.board.name} on {self.port} refused {request!r}: {reply}"
            )
        return reply

    def _check(self, identifier: int) -> None:
        if identifier not in range(BlinkenBoard.LED_COUNT):
            raise ValueError(f"the Blinken board has LEDs 0 to 3, not {identifier!r}")

    async def get_led_state(self, identifier: int) -> bool:
        """Ask the board whether an LED is on."""
        self._check(identifier)
        return await self._command(f"L{identifier}?") == "1"

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Turn an LED on or off."""
        self._check(identifier)
        await self._command(f"L{identifier} {int(state)}")
