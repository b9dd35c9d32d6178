"""The hardware backend of the SR Ruggeduino running SR firmware 1 (or a team's own).

Handshake: after the port opens the board reboots, so ``v`` is sent and re-sent while
the answer is empty or late (at most 26 attempts, 1.25 s each, times the time scale);
the text after the last ``:`` of the answer must be ``1``. The pins' initial modes are
then applied by the board's ``setup()``.
"""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.hardware.arduino import ArduinoHardwareBackend
from j5aio.backends.hardware.serial_backend import scaled
from j5aio.backends.hardware.sr.v4 import ruggeduino_fw1_codec as codec
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


class SRV4RuggeduinoHardwareBackend(StringCommandComponentInterface, ArduinoHardwareBackend):
    """Drives a Ruggeduino over its single-character protocol (firmware 1)."""

    board = Ruggeduino
    #: Firmware 1 takes any pin letter up to ``t`` (pin 19) in its digital commands.
    ANALOGUE_PINS_DIGITAL: ClassVar[bool] = True

    #: How many times ``v`` is sent before the board is declared silent.
    VERSION_ATTEMPTS: ClassVar[int] = 26

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
        for _ in range(self.VERSION_ATTEMPTS):
            try:
                line = await self._exchange(codec.VERSION_QUERY, _LINE, timeout=wait)
            except CommunicationTimeoutError:
                continue
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
        self._firmware_version = version.version.strip()

    async def _command(self, command: bytes) -> bytes:
        """Send one command and return its reply line (often empty)."""
        return await self._exchange(command, _LINE)

    async def _apply_pin(self, identifier: int, *, mode_changed: bool) -> None:
        state = self._pins.digital(identifier)
        if state.mode is GPIOPinMode.DIGITAL_OUTPUT:
            if mode_changed:
                await self._command(codec.encode_mode(identifier, state.mode))
            await self._command(codec.encode_digital_write(identifier, state.level))
        elif state.mode is GPIOPinMode.ANALOGUE_INPUT:  # A0-A5 back from a digital mode
            await self._command(codec.encode_mode(identifier, GPIOPinMode.DIGITAL_INPUT))
        else:
            await self._command(codec.encode_mode(identifier, state.mode))

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
