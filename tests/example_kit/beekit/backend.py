"""The Bee Board's hardware backend: its line protocol over a serial port."""

from __future__ import annotations

from typing import ClassVar

import anyio

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports import read_line
from j5aio.components.button import ButtonInterface
from j5aio.components.led import LEDInterface
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState
from j5aio.errors import (
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)

from .boards import BeeBoard

__all__ = ["BeeBackend"]

#: The firmware major versions this backend speaks.
SUPPORTED_VERSIONS = ("2",)

#: Motor steps each way: a power of 1 is 100 steps.
MOTOR_STEPS = 100

_LINE = read_line()


class BeeBackend(SerialHardwareBackend[BeeBoard], MotorInterface, LEDInterface, ButtonInterface):
    """Drives a Bee Board through its serial port.

    :class:`SerialHardwareBackend` brings discovery by USB identity, ``attach(port)`` and
    ``from_stream(stream, ...)``; this class adds the handshake and the interfaces.
    """

    #: Motor steps each way, as the firmware counts them (a power of 1).
    MOTOR_STEPS: ClassVar[int] = MOTOR_STEPS

    board = BeeBoard

    BAUDRATE: ClassVar[int] = 57_600
    #: The USB IDs of the board's USB-serial adapter (imaginary ones).
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x1209, 0xBEE0)})

    #: How often the button is read while waiting for a press, in seconds.
    BUTTON_POLL_INTERVAL: ClassVar[float] = 0.02

    _powers: list[float]
    _led: bool

    async def _handshake(self, *, time_scale: float) -> None:
        """Ask the board who it is, check that we speak its firmware, and note its version."""
        self._powers = [0.0] * BeeBoard.MOTOR_COUNT
        self._led = False
        try:
            identity = await self._ask(b"?")
        except UnexpectedReplyError:
            # Bytes left by another kind's probe (attach asks j5aio's own kinds first)
            # made the board refuse the line: ask once more, on a clean line.
            identity = await self._ask(b"?")
        name, _, version = identity.partition(":")
        if name != "BEE":
            raise UnexpectedReplyError(f"{self.port} is not a Bee Board: it says {name!r}")
        if version.split(".")[0] not in SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, SUPPORTED_VERSIONS)
        self.firmware_version = version

    async def _ask(self, command: bytes) -> str:
        """Send one command line and return the board's reply line."""
        reply = (await self.exchange(command + b"\n", _LINE)).decode("ascii", "replace")
        if reply.startswith("ERR"):
            raise UnexpectedReplyError(f"the Bee Board on {self.port} refused {command!r}: {reply}")
        return reply

    async def _ask_ok(self, command: bytes) -> None:
        reply = await self._ask(command)
        if reply != "OK":
            raise UnexpectedReplyError(f"expected OK after {command!r}, got {reply!r}")

    # -- motors -------------------------------------------------------------------------

    def _check_motor(self, identifier: int) -> None:
        if identifier not in range(BeeBoard.MOTOR_COUNT):
            raise ValueError(f"the Bee Board has motors 0 and 1, not {identifier!r}")

    async def get_motor_state(self, identifier: int) -> MotorState:
        """Return the power last set (the board cannot report it)."""
        self._check_motor(identifier)
        return self._powers[identifier]

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Run a motor at ``power``, rounded to the nearest of the board's steps."""
        self._check_motor(identifier)
        if isinstance(power, MotorSpecialState):
            raise NotSupportedByHardwareError(
                f"the Bee Board's motors cannot {power.name}: set a power (0 stops a motor)",
            )
        steps = round(power * self.MOTOR_STEPS)
        await self._ask_ok(b"M%d %d" % (identifier, steps))
        self._powers[identifier] = steps / self.MOTOR_STEPS

    # -- the LED ------------------------------------------------------------------------

    def _check_single(self, identifier: int, what: str) -> None:
        if identifier != 0:
            raise ValueError(f"the Bee Board has {what} 0 only, not {identifier!r}")

    async def get_led_state(self, identifier: int) -> bool:
        """Return the state last set (the board cannot report it)."""
        self._check_single(identifier, "LED")
        return self._led

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or darken the LED."""
        self._check_single(identifier, "LED")
        await self._ask_ok(b"L%d" % state)
        self._led = state

    # -- the button ---------------------------------------------------------------------

    async def get_button_state(self, identifier: int) -> bool:
        """Read whether the button is held."""
        self._check_single(identifier, "button")
        reply = await self._ask(b"B")
        if reply not in ("B0", "B1"):
            raise UnexpectedReplyError(f"expected B0 or B1 for the button, got {reply!r}")
        return reply == "B1"

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Read the button until it is held (cancel the call to stop waiting)."""
        while not await self.get_button_state(identifier):  # noqa: ASYNC110 - polling a board
            await anyio.sleep(self.BUTTON_POLL_INTERVAL)
