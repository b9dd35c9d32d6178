"""The Blinkenboard's hardware backend: the line protocol over a serial link."""

from __future__ import annotations

from typing import ClassVar

import anyio

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports import SerialLink, read_line
from j5aio.components.button import ButtonInterface
from j5aio.components.led import LEDInterface
from j5aio.errors import UnexpectedReplyError, UnsupportedFirmwareError

from .blinkenboard import BlinkenBoard

#: The firmware versions this backend speaks.
SUPPORTED_VERSIONS = ("1",)

_LINE = read_line()


class BlinkenBoardBackend(LEDInterface, ButtonInterface, SerialHardwareBackend):
    """Drives a Blinkenboard through its serial port.

    :class:`SerialHardwareBackend` brings discovery, ``attach(port)`` and
    ``from_stream(stream, ...)``; this class adds the handshake and the interfaces.
    """

    board = BlinkenBoard

    #: The USB IDs of the board's USB-serial adapter (imaginary ones).
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x1209, 0xB117)})

    #: How often the button is read while waiting for a press, in seconds.
    BUTTON_POLL_INTERVAL: ClassVar[float] = 0.02

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._leds = [False] * BlinkenBoard.LED_COUNT

    async def _handshake(self, *, time_scale: float) -> None:
        """Ask the board who it is, and check that we speak its firmware."""
        name, _, version = (await self._ask(b"?")).partition(":")
        if name != "BLINKEN":
            raise UnexpectedReplyError(f"{self.port} is not a Blinkenboard: it says {name!r}")
        if version.split(".")[0] not in SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, SUPPORTED_VERSIONS)
        self._firmware_version = version

    async def _ask(self, command: bytes) -> str:
        """Send one command line and return the board's reply line."""
        reply = (await self._exchange(command + b"\n", _LINE)).decode("ascii", "replace")
        if reply.startswith("ERR"):
            raise UnexpectedReplyError(f"the Blinkenboard refused {command!r}: {reply}")
        return reply

    def _check_led(self, identifier: int) -> None:
        if identifier not in range(BlinkenBoard.LED_COUNT):
            raise ValueError(f"the Blinkenboard has LEDs 0 to 3, not {identifier!r}")

    async def get_led_state(self, identifier: int) -> bool:
        """Return the state last set (the board cannot report it)."""
        self._check_led(identifier)
        return self._leds[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or darken an LED."""
        self._check_led(identifier)
        reply = await self._ask(b"L%d%d" % (identifier, state))
        if reply != "OK":
            raise UnexpectedReplyError(f"expected OK after setting LED {identifier}, got {reply!r}")
        self._leds[identifier] = state

    def make_safe_now(self, timeout: float) -> bool:
        """Darken every LED at once, synchronously: the safety net's last word at exit.

        The same safe state as :meth:`BlinkenBoard.make_safe`, sent without waiting for
        the replies (the link drains them if it is used again).
        """
        if self._link.is_closed:
            return False
        commands = b"".join(b"L%d0\n" % led for led in range(BlinkenBoard.LED_COUNT))
        self._link.send_now(commands, timeout=timeout)
        self._leds = [False] * BlinkenBoard.LED_COUNT
        return True

    async def get_button_state(self, identifier: int) -> bool:
        """Read whether the button is held."""
        if identifier != 0:
            raise ValueError(f"the Blinkenboard has button 0 only, not {identifier!r}")
        reply = await self._ask(b"B")
        if reply not in ("B0", "B1"):
            raise UnexpectedReplyError(f"expected B0 or B1 for the button, got {reply!r}")
        return reply == "B1"

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Read the button until it is held (cancel the call to stop waiting)."""
        while not await self.get_button_state(identifier):  # noqa: ASYNC110 - polling a board
            await anyio.sleep(self.BUTTON_POLL_INTERVAL)
