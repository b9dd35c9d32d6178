"""The hardware backend of the SourceBots Arduino, 2019 line protocol (2019.6.0 and later).

Handshake: the board reboots when the port opens; lines are read until the first
non-empty one, which must be ``# Booted``, then the version line
(``# SBDuino GPIO v2019.8.0``), all within 33 s times the time scale. The pins' initial
modes are then applied by the board's ``setup()``.

Correlation guarantee: while no request is outstanding the board's next reply is the
answer to the next request, so requests go as the firmware's own examples have them
(``R 2``), with no id to lengthen them on the wire. Once a request has timed out (or an
exchange did not finish), its reply may still come, so the next request carries a
request id (``@<n>`` and a space, cycling through 1 to 32767) and a reply is taken only if its echo
or final line carries that id. A reply that arrives after its request timed out is
skipped however late it comes, so it is never taken as another request's answer (unless
32767 tagged requests have gone meanwhile); the board answers in order, so once the
tagged request's reply has come, the line is clean and requests go plain again.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, ClassVar

import anyio

import j5aio.backends.hardware.sb.arduino_2019_codec as codec
from j5aio.backends.hardware.arduino import ArduinoHardwareBackend
from j5aio.backends.hardware.arduino_pins import DIGITAL_PINS, DigitalPinState
from j5aio.backends.hardware.serial_backend import scaled
from j5aio.backends.hardware.transports.readers import ReplyReader
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.components.derived.ultrasound import UltrasoundInterface
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.servo import ServoInterface, ServoPosition
from j5aio.errors import (
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
)

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta

__all__ = ["SBArduinoHardwareBackend"]


class SBArduinoHardwareBackend(
    ServoInterface,
    UltrasoundInterface,
    ArduinoHardwareBackend[SBArduinoBoard],
):
    """Drives a SourceBots Arduino over the 2019 line protocol."""

    board = SBArduinoBoard

    ANALOGUE_CHANNELS: ClassVar[int] = codec.ANALOGUE_CHANNELS
    #: The longest wait for ``# Booted`` and the version line (j5 allowed about 33 s).
    BOOT_TIMEOUT: ClassVar[float] = 33.0
    #: Identification waits about 3.3 s for the banner: an Uno's bootloader hands over
    #: within 2 s, and a Ruggeduino (which prints nothing) is not kept waiting 33 s.
    IDENTIFY_TIME_SCALE: ClassVar[float] = 0.1
    #: The longest wait for an ultrasound reading (the firmware's ``pulseIn`` can take
    #: over a second with no echo).
    ULTRASOUND_TIMEOUT: ClassVar[float] = 3.0

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._servos: list[ServoPosition] = [None] * codec.SERVO_COUNT
        self._request_id = 0

    def reset_board_state(self) -> None:
        """Forget what was remembered: pins are inputs and servos unpowered after a reset."""
        super().reset_board_state()
        self._servos = [None] * codec.SERVO_COUNT

    async def _handshake(self, *, time_scale: float) -> None:
        limit = scaled(self.BOOT_TIMEOUT, time_scale)
        try:
            with anyio.fail_after(limit):
                line = b""
                while not line.strip():
                    line = await self._link.read_line(timeout=limit)
                if line.rstrip() != codec.BOOT_LINE.encode():
                    raise UnexpectedReplyError(
                        f"{self.board.name} on {self.port} did not boot as expected: its "
                        f"first line was {line!r}, not {codec.BOOT_LINE!r}",
                    )
                version_line = await self._link.read_line(timeout=limit)
        except (TimeoutError, CommunicationTimeoutError):
            raise CommunicationTimeoutError(
                f"{self.board.name} on {self.port} did not finish booting within {limit:g} s: "
                "is it powered, and does opening the port reset it?",
            ) from None
        version = codec.parse_version_line(version_line)
        codec.check_version(version)
        self.firmware_version = version

    def _next_request_id(self) -> int:
        self._request_id = self._request_id % codec.MAX_REQUEST_ID + 1
        return self._request_id

    async def _command(
        self,
        request: bytes,
        timeout: float | None = None,
        then: Callable[[codec.Reply], None] | None = None,
        *,
        acknowledged_only: bool = False,
    ) -> codec.Reply:
        """Send a request (with a fresh request id) and return the data of its reply.

        :param then: called with the reply once the board has accepted the command
            (``+ OK``), even if the caller has been cancelled meanwhile.
        :param acknowledged_only: the reply carries no value (a pin or servo set): inside
            :func:`~j5aio.backends.acknowledgements.acknowledge_later` the command returns
            an empty reply once written, and the reply is checked before the next request.
        """

        def tagged() -> tuple[bytes, ReplyReader[list[bytes]]]:
            with_id = codec.with_request_id(request, self._next_request_id())
            return with_id, codec.reply_to(with_id)

        def parse(lines: list[bytes]) -> codec.Reply:
            try:
                reply = codec.parse_reply(lines)
            except UnexpectedReplyError:
                self._link.mark_dirty()  # out of step? the next request carries an id
                raise
            if then is not None:
                then(reply)
            return reply

        if acknowledged_only:
            await self.command(request, codec.REPLY, timeout, then=parse, when_dirty=tagged)
            return codec.Reply(())
        return await self.exchange(request, codec.REPLY, timeout, then=parse, when_dirty=tagged)

    async def _apply_pin(
        self, identifier: int, wanted: DigitalPinState, *, mode_changed: bool
    ) -> None:
        await self._command(
            codec.encode_pin_state(identifier, wanted.mode, wanted.level),
            then=lambda _: self._remember_pin(identifier, wanted.mode, wanted.level),
            acknowledged_only=True,
        )

    async def _read_digital(self, identifier: int) -> bool:
        return codec.parse_digital(await self._command(codec.encode_digital_read(identifier)))

    async def _read_analogue(self, identifier: int) -> float:
        return codec.parse_analogue(await self._command(codec.encode_analogue_read()), identifier)

    # -- servos -------------------------------------------------------------------------

    def _check_servo(self, identifier: int) -> None:
        if identifier not in range(codec.SERVO_COUNT):
            raise ValueError(
                f"{self.board.name} has servos 0 to {codec.SERVO_COUNT - 1}, not {identifier!r}",
            )

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return the position last set on a servo (the board cannot report it)."""
        self._check_servo(identifier)
        return self._servos[identifier]

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Move a servo (``S``; firmware 2019.6.0 with the servo shield only)."""
        self._check_servo(identifier)
        request = codec.encode_servo(identifier, position)

        def remember(_: codec.Reply) -> None:
            self._servos[identifier] = position

        await self._command(request, then=remember, acknowledged_only=True)

    # -- ultrasound ---------------------------------------------------------------------

    def _check_ultrasound_pins(self, trigger: int, echo: int) -> None:
        for pin in (trigger, echo):
            self._pins.mode(pin)  # ValueError for a pin the board does not have
            if pin not in DIGITAL_PINS:
                raise NotSupportedByHardwareError(
                    f"{self.board.name} drives ultrasound sensors on digital pins "
                    f"{DIGITAL_PINS.start} to {DIGITAL_PINS.stop - 1} only, not pin {pin}",
                )

    def _ultrasound_done(self, trigger: int, echo: int) -> None:
        """Remember the modes the firmware left the pins in: trigger low output, echo input."""
        self._remember_pin(trigger, GPIOPinMode.DIGITAL_OUTPUT, False)
        self._remember_pin(echo, GPIOPinMode.DIGITAL_INPUT, self._pins.digital(echo).level)

    async def _ultrasound(self, trigger: int, echo: int, *, distance: bool) -> codec.Reply:
        self._check_ultrasound_pins(trigger, echo)
        request = codec.encode_ultrasound(trigger, echo, distance=distance)
        return await self._command(
            request, self.ULTRASOUND_TIMEOUT, then=lambda _: self._ultrasound_done(trigger, echo)
        )

    async def get_ultrasound_pulse(
        self,
        trigger_pin_identifier: int,
        echo_pin_identifier: int,
    ) -> timedelta | None:
        """Return the echo time of an ultrasound sensor (``T``), or ``None`` with no echo."""
        reply = await self._ultrasound(trigger_pin_identifier, echo_pin_identifier, distance=False)
        return codec.parse_ultrasound_pulse(reply)

    async def get_ultrasound_distance(
        self,
        trigger_pin_identifier: int,
        echo_pin_identifier: int,
    ) -> float | None:
        """Return the distance in metres (``U``), or ``None`` with no echo."""
        reply = await self._ultrasound(trigger_pin_identifier, echo_pin_identifier, distance=True)
        return codec.parse_ultrasound_distance(reply)
