"""The hardware backend of the SR Ruggeduino running SR firmware 1 (or a team's own).

Handshake: after the port opens the board reboots, so ``v`` is sent and re-sent while
the answer is empty or late (at most 26 attempts, 1.25 s each, times the time scale);
the text after the last ``:`` of the answer must be ``1``. The pins' initial modes are
then applied by the board's ``setup()``.

Correlation guarantee: a reply names nothing of its request (``h``, ``l``, a number or an
empty line), so after a timeout the link resynchronises with ``v``, whose answer is the
version line read in the handshake: every byte up to and including that answer is
discarded, and since the board answers in order, nothing owed to an earlier request can
come after it. While a reply that timed out may still come, each request is sent
between two such probes (see :meth:`.SerialLink.set_resync_line`), so that even a reply
that comes after later ones is never taken. ``v`` is sent only by the handshake and by
these probes, so the one
remaining risk is a probe that itself timed out; its answer, a version line, is no
valid reply to any pin command, so it fails as an :class:`~j5aio.errors.UnexpectedReplyError`
rather than being taken as a value. (A team's own firmware answering ``v`` with a line
that other commands also send would weaken this; string commands get no guarantee.)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import ClassVar

import j5aio.backends.hardware.sr.v4.ruggeduino_fw1_codec as codec
from j5aio.backends.hardware.arduino import ArduinoHardwareBackend
from j5aio.backends.hardware.arduino_pins import DigitalPinState
from j5aio.backends.hardware.serial_backend import scaled
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.string_command import StringCommandComponentInterface
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnsupportedFirmwareError,
)

__all__ = ["SRV4RuggeduinoHardwareBackend"]

_LINE = read_line()
_LINE_WITH_END = read_line(keep_ends=True)


class SRV4RuggeduinoHardwareBackend(
    StringCommandComponentInterface, ArduinoHardwareBackend[Ruggeduino],
):
    """Drives a Ruggeduino over its single-character protocol (firmware 1)."""

    board = Ruggeduino
    #: Firmware 1 takes any pin letter up to ``t`` (pin 19) in its digital commands.
    ANALOGUE_PINS_DIGITAL: ClassVar[bool] = True

    #: How many times ``v`` is sent before the board is declared silent.
    VERSION_ATTEMPTS: ClassVar[int] = 26
    #: Identification asks for the version for about 5 s rather than 33 s.
    IDENTIFY_TIME_SCALE: ClassVar[float] = 0.15

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._version: codec.RuggeduinoVersion | None = None

    @property
    def is_official_firmware(self) -> bool:
        """Whether the board runs SR's own firmware (``SRduino``)."""
        return self._version is not None and self._version.is_official

    async def _handshake(self, *, time_scale: float) -> None:
        wait = scaled(self.DEFAULT_TIMEOUT, time_scale)
        line = b""
        retried = False
        for _ in range(self.VERSION_ATTEMPTS):
            try:
                raw = await self.exchange(codec.VERSION_QUERY, _LINE_WITH_END, timeout=wait)
            except CommunicationTimeoutError:
                retried = True
                continue
            line = raw.rstrip(b"\r\n")
            if line.strip():
                break
        else:
            raise CommunicationTimeoutError(
                f"{self.board.name} on {self.port} did not answer the version query after "
                f"{self.VERSION_ATTEMPTS} tries: is it powered, and does it run SR firmware "
                "(or a firmware that answers 'v')?",
            )
        version = codec.parse_version(line)
        if version.version.strip() not in codec.SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(
                self.board.name, version.version, codec.SUPPORTED_VERSIONS
            )
        self._version = version
        self.firmware_version = version.version.strip()
        if retried:
            # A 'v' that timed out while the board booted may still be answered, by the
            # very line the probe below waits for: let it pass first.
            await self._link.drain()
        self._link.set_resync_line(lambda: (codec.VERSION_QUERY, line))

    async def _command(self, command: bytes) -> bytes:
        """Send one command and return its reply line."""
        return await self.exchange(command, _LINE)

    async def _tell(self, command: bytes, then: Callable[[], None]) -> None:
        """Send a command whose reply line (empty) only acknowledges it.

        :param then: called once the reply has arrived, even for a cancelled caller.
            Inside :func:`~j5aio.backends.acknowledgements.acknowledge_later` the command
            returns once written, and the reply is read before the next request.
        """

        def done(_line: bytes) -> None:
            then()

        await self.command(command, _LINE, then=done)

    async def _apply_pin(
        self, identifier: int, wanted: DigitalPinState, *, mode_changed: bool
    ) -> None:
        current = self._pins.digital(identifier)
        if wanted.mode is GPIOPinMode.DIGITAL_OUTPUT:
            if mode_changed:
                # An output drives its latch: high after a pull-up input, low after a
                # plain input, its last level if it was an output already.
                latch = (
                    current.level
                    if current.mode is GPIOPinMode.DIGITAL_OUTPUT
                    else current.mode is GPIOPinMode.DIGITAL_INPUT_PULLUP
                )
                await self._tell(
                    codec.encode_mode(identifier, wanted.mode),
                    then=lambda: self._remember_pin(identifier, wanted.mode, latch),
                )
            await self._tell(
                codec.encode_digital_write(identifier, wanted.level),
                then=lambda: self._remember_pin(identifier, wanted.mode, wanted.level),
            )
        elif wanted.mode is GPIOPinMode.ANALOGUE_INPUT:  # A0-A5 back from a digital mode
            await self._tell(
                codec.encode_mode(identifier, GPIOPinMode.DIGITAL_INPUT),
                then=lambda: self._remember_pin(identifier, wanted.mode, False),
            )
        else:
            await self._tell(
                codec.encode_mode(identifier, wanted.mode),
                then=lambda: self._remember_pin(identifier, wanted.mode, current.level),
            )

    async def _read_digital(self, identifier: int) -> bool:
        return codec.parse_digital(await self._command(codec.encode_digital_read(identifier)))

    async def _read_analogue(self, identifier: int) -> float:
        return codec.parse_analogue(await self._command(codec.encode_analogue_read(identifier)))

    async def execute_string_command(self, command: str) -> str:
        """Send ``command`` as it is to a team's own firmware and return its reply line.

        :raises NotSupportedByHardwareError: the board runs SR's own firmware, which has
            no string commands.
        :raises CommunicationError: no reply line came in time.
        """
        if self.is_official_firmware:
            raise NotSupportedByHardwareError(
                f"{self.board.name} runs SR's own firmware, which takes no string commands; "
                "load a firmware of your own to use them",
            )
        try:
            data = command.encode("utf-8")
        except UnicodeEncodeError as exc:  # pragma: no cover - str always encodes to UTF-8
            raise CommunicationError(f"cannot send {command!r}: {exc}") from exc
        reply = await self._command(data)
        return reply.decode("utf-8", errors="replace")
