"""Hardware backends of the SR v4 Servo Board with the serial firmware (4.3, and SB's 4.4).

The board is a USB CDC serial port with the same USB ids as firmware 2 (``1BDA:0011``);
firmware 2 is not a serial port, so serial discovery only ever finds the text firmware.
The handshake asks ``*IDN?`` and keeps the board only if its version is one the backend
supports; the version tells SR's 4.3 (12 servos, :class:`SRV4ServoBoardFw4HardwareBackend`)
from the SourceBots fork 4.4 (8 servos, :class:`SBServoBoardHardwareBackend`).
:data:`SERVO_FW4_BACKENDS` maps each version to its backend, for code that identifies
a port first. Nothing is sent to the servos at start-up: they keep whatever the board
was doing.

Positions map onto each servo's pulse limits (until changed, 1000 to 2000 µs on SR's
firmware and 350 to 1980 µs on SourceBots', as sr-robot3 and sbot map them). Every
read asks the board, so nothing about the board is cached. The state kept here is what
the handshake found (firmware, version, asset tag: running
:meth:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend._handshake` again
refreshes it) and
:attr:`~j5aio.backends.hardware.sr.v4.servo_board_fw4._ServoBoardFw4Backend.pulse_limits`,
the user's own setting, which a repeated handshake keeps. So after a reconnection, running
the handshake again is all there is to do.
"""

from __future__ import annotations

from collections.abc import Awaitable, Mapping
from types import MappingProxyType
from typing import ClassVar, Final

import j5aio.backends.hardware.sr.v4.servo_fw4_codec as codec
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.text_protocol import echo_probe
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sb.servo_board import SBServoBoard
from j5aio.boards.sr.v4.servo_board_fw4 import ServoBoardFw4
from j5aio.components.flag import FlagInterface
from j5aio.components.pulse_servo import PulseLimits, PulseServoInterface
from j5aio.components.servo import ServoPosition
from j5aio.components.supply_sensor import SupplySensorInterface
from j5aio.errors import BoardDisconnectionError

__all__ = [
    "SERVO_FW4_BACKENDS",
    "SBServoBoardHardwareBackend",
    "SRV4ServoBoardFw4HardwareBackend",
]

# A reply is one line; the firmware's whole reply buffer is 64 bytes.
_REPLY: Final = read_line(max_length=64)


class _ServoBoardFw4Backend(
    PulseServoInterface, SupplySensorInterface, FlagInterface, SerialHardwareBackend,
):
    """What both firmwares share; subclasses name the board and the supported version."""

    board = ServoBoardFw4
    DEFAULT_TIMEOUT: ClassVar[float] = 0.5
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(codec.VID, codec.PID)})
    USB_MANUFACTURER: ClassVar[str | None] = codec.MANUFACTURER
    USB_PRODUCT: ClassVar[str | None] = codec.PRODUCT
    #: The firmware versions this backend drives.
    SUPPORTED_VERSIONS: ClassVar[tuple[str, ...]] = ()

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._firmware: codec.Firmware | None = None
        self._asset_tag: str | None = None
        self._limits: list[PulseLimits] = []

    # -- handshake and state -------------------------------------------------------------

    async def _handshake(self, *, time_scale: float) -> None:
        reply = await self._query(codec.IDENTIFY)
        if reply.startswith(b"NACK:"):
            # Leftovers of another program's (or kind's) probe, ahead of our line on a
            # port that does not reset when opened: the NACK ended them; ask again.
            reply = await self._query(codec.IDENTIFY)
        identity = codec.parse_identity(self.board.name, reply)
        firmware = codec.firmware_for(self.board.name, identity.version, self.SUPPORTED_VERSIONS)
        self._firmware = firmware
        self.firmware_version = identity.version
        self._asset_tag = identity.asset_tag
        # The limits are the user's: a handshake run again (the board came back) keeps them.
        if len(self._limits) != firmware.servo_count:
            self._limits = [firmware.default_limits] * firmware.servo_count

    def _link_ready(self) -> None:
        # Late replies: after a timeout, resynchronise with an echoed nonce (as the
        # other text firmwares; see :mod:`.text_backend`).
        self._link.set_resync_line(echo_probe)

    @property
    def firmware(self) -> codec.Firmware:
        """The firmware the handshake found."""
        if self._firmware is None:
            raise RuntimeError(f"{self.board.name} on {self.port} has not been identified yet")
        return self._firmware

    @property
    def asset_tag(self) -> str | None:
        """The asset tag the board reported in its identity."""
        return self._asset_tag

    @property
    def pulse_limits(self) -> tuple[PulseLimits, ...]:
        """Each servo's pulse limits: the user's setting, kept across reconnections."""
        return tuple(self._limits)

    async def _query(self, request: bytes) -> bytes:
        return await self.exchange(request, _REPLY)

    async def _act(self, request: bytes) -> None:
        """Send an action and check its ``ACK`` (later, inside ``acknowledge_later()``)."""

        def acknowledged(reply: bytes) -> None:
            codec.check_ack(self.board.name, request, reply)

        # What the backend's command() does, written out (a servo's every move takes
        # this path): a lost board is looked for first, and one that vanishes under the
        # call is handed to the reconnection policy.
        try:
            if self._lost or self._closed_for_good:
                await self._check_connected()
            await self._link.command(request, _REPLY, then=acknowledged)
        except BoardDisconnectionError as lost:

            def again() -> Awaitable[None]:  # the link is looked up anew
                return self._link.command(request, _REPLY, then=acknowledged)

            await self._retry_after(lost, again, idempotent=True)

    def _check_servo(self, identifier: int) -> None:
        codec.check_servo(self.firmware, identifier)

    # -- servos --------------------------------------------------------------------------

    async def get_servo_pulse_range(self, identifier: int) -> PulseLimits:
        """Return the firmware's shortest and longest pulse, in µs."""
        self._check_servo(identifier)
        return (self.firmware.min_pulse, self.firmware.max_pulse)

    async def get_servo_pulse_limits(self, identifier: int) -> PulseLimits:
        """Return the pulses positions -1 and 1 give servo ``identifier``, in µs."""
        self._check_servo(identifier)
        return self._limits[identifier]

    async def set_servo_pulse_limits(self, identifier: int, limits: PulseLimits) -> None:
        """Map positions -1 and 1 of servo ``identifier`` to ``limits`` (sends nothing).

        :raises ValueError: the limits are not increasing, or outside the firmware's range.
        """
        self._check_servo(identifier)
        lower, upper = limits
        firmware = self.firmware
        if not firmware.min_pulse <= lower < upper <= firmware.max_pulse:
            raise ValueError(
                f"{self.board.name} takes pulse limits within {firmware.min_pulse} to "
                f"{firmware.max_pulse} µs, lower first; got {lower} to {upper} µs",
            )
        self._limits[identifier] = (lower, upper)

    async def get_servo_pulse_width(self, identifier: int) -> int | None:
        """Ask the board for servo ``identifier``'s pulse, in µs (``None``: disabled)."""
        firmware = self.firmware
        request = codec.encode_get(firmware, identifier)
        return codec.parse_pulse(self.board.name, request, await self._query(request), firmware)

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return the position of the pulse the board gives (``None``: disabled).

        The pulse is read back in 5 µs steps, so the position is within 0.01 of the one
        set with the default limits.
        """
        pulse = await self.get_servo_pulse_width(identifier)
        if pulse is None:
            return None
        return codec.position_for_pulse(pulse, self._limits[identifier])

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Send ``SERVO:<n>:SET:<µs>`` for a position, ``SERVO:<n>:DISABLE`` for ``None``."""
        firmware = self.firmware
        if position is None:
            await self._act(codec.encode_disable(firmware, identifier))
            return
        codec.check_servo(firmware, identifier)  # before the index: -1 is an index too
        limits = self._limits[identifier]
        if type(position) is float and -1.0 <= position <= 1.0:
            # The path of every move: what pulse_for_position and encode_set do, written
            # out (the limits are within the firmware's range: they were checked when set).
            low, high = limits
            pulse = int((position + 1) * (high - low) / 2 + low)
            await self._act(f"SERVO:{identifier}:SET:{pulse}\n".encode("ascii"))
            return
        pulse = codec.pulse_for_position(position, limits)
        await self._act(codec.encode_set(firmware, identifier, pulse))

    async def reset(self) -> None:
        """Disable every servo (``*RESET``)."""
        await self._act(codec.RESET)

    # -- supply and flags ----------------------------------------------------------------

    @staticmethod
    def _check_only(kind: str, identifier: int, valid: range) -> None:
        if isinstance(identifier, bool) or identifier not in valid:
            raise ValueError(
                f"the servo board has {kind} {valid.start} to {valid.stop - 1}, "
                f"not {identifier!r}",
            )

    async def get_supply_voltage(self, identifier: int) -> float:
        """Return the servo rail's voltage (``SERVO:V?``), in volts."""
        self._check_only("supply sensor", identifier, range(1))
        reply = await self._query(codec.READ_VOLTAGE)
        return codec.parse_milli(self.board.name, codec.READ_VOLTAGE, reply)

    async def get_supply_current(self, identifier: int) -> float:
        """Return the servo rail's current (``SERVO:I?``), in amps."""
        self._check_only("supply sensor", identifier, range(1))
        reply = await self._query(codec.READ_CURRENT)
        return codec.parse_milli(self.board.name, codec.READ_CURRENT, reply)

    async def get_flag_state(self, identifier: int) -> bool:
        """Return flag 0 (power good) or 1 (watchdog failed) from ``*STATUS?``."""
        self._check_only("flags", identifier, range(2))
        status = codec.parse_status(self.board.name, await self._query(codec.READ_STATUS))
        if identifier == ServoBoardFw4.POWER_GOOD:
            return status.power_good
        return status.watchdog_failed


class SRV4ServoBoardFw4HardwareBackend(_ServoBoardFw4Backend):
    """Drives an SR v4 Servo Board running Student Robotics firmware 4.3 (12 servos)."""

    board = ServoBoardFw4
    SUPPORTED_VERSIONS: ClassVar[tuple[str, ...]] = ("4.3",)


class SBServoBoardHardwareBackend(_ServoBoardFw4Backend):
    """Drives a servo board running the SourceBots fork of the firmware, 4.4 (8 servos)."""

    board = SBServoBoard
    SUPPORTED_VERSIONS: ClassVar[tuple[str, ...]] = ("4.4",)


#: The backend of each servo board firmware version, for code that identifies a port first.
SERVO_FW4_BACKENDS: Final[Mapping[str, type[_ServoBoardFw4Backend]]] = MappingProxyType(
    {"4.3": SRV4ServoBoardFw4HardwareBackend, "4.4": SBServoBoardHardwareBackend},
)
