"""The hardware backend of the SR Arduino running SR firmware 2 (``SRduino:2``).

Handshake: the board reboots when the port opens, so ``v`` is sent and re-sent while the
answer is empty, late or garbled (at most 26 attempts, 1.25 s each, times the time
scale); the answer must be ``<name>:2``. ``SRduino`` is SR's own firmware; another name
is a team's own firmware that speaks the same protocol. The pins' initial modes are then
applied by the board's ``setup()``.
"""

from __future__ import annotations

from typing import ClassVar

import j5aio.backends.hardware.sr.v4.arduino_fw2_codec as codec
from j5aio.backends.hardware.arduino_gpio import ArduinoGPIOBackend, PinCodec
from j5aio.backends.hardware.serial_backend import scaled
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4.arduino import SRArduinoBoard
from j5aio.components.string_command import StringCommandComponentInterface
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)

__all__ = ["SRArduinoHardwareBackend"]

_LINE = read_line()


class SRArduinoHardwareBackend(
    StringCommandComponentInterface, ArduinoGPIOBackend[SRArduinoBoard],
):
    """Drives an SR Arduino over the single-character protocol (firmware 2)."""

    board = SRArduinoBoard
    CODEC: ClassVar[PinCodec] = codec

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._version: codec.RuggeduinoVersion | None = None

    @property
    def is_official_firmware(self) -> bool:
        """Whether the board runs SR's own firmware (``SRduino``)."""
        return self._version is not None and self._version.is_official

    @classmethod
    async def identify_firmware(
        cls, link: SerialLink, *, time_scale: float = 1.0, attempts: int | None = None,
    ) -> str:
        """Send ``v`` until the board answers a version line; return the version (``2``).

        :raises UnsupportedFirmwareError: the board answers another version (``SRduino:1``).
        :raises CommunicationError: no version line after every attempt.
        """
        return (await cls._read_version(link, time_scale, attempts)).version

    @classmethod
    async def _read_version(
        cls, link: SerialLink, time_scale: float, attempts: int | None,
    ) -> codec.RuggeduinoVersion:
        wait = scaled(cls.DEFAULT_TIMEOUT, time_scale)
        tries = cls.IDENTIFY_ATTEMPTS if attempts is None else attempts
        last: CommunicationError | None = None
        for _ in range(tries):
            try:
                line = await link.exchange(codec.VERSION_QUERY, _LINE, timeout=wait)
                if not line:
                    continue  # the sketch is up, but the 'v' went to the bootloader
                version = codec.parse_version(line)
            except (CommunicationTimeoutError, UnexpectedReplyError) as exc:
                last = exc
                continue
            if version.version not in codec.SUPPORTED_VERSIONS:
                raise UnsupportedFirmwareError(
                    cls.board.name, version.version, codec.SUPPORTED_VERSIONS,
                )
            if last is not None:
                # An earlier 'v' may still be answered, by the very line that the
                # resynchronisation probe waits for (see _link_ready): let it pass.
                await link.drain()
            return version
        raise CommunicationTimeoutError(
            f"{cls.board.name} on {link.name} did not answer the version query after "
            f"{tries} tries (last: {last}): is it powered, and does it run SR firmware 2?",
        )

    async def _handshake(self, *, time_scale: float) -> None:
        self._version = await self._read_version(self._link, time_scale, None)
        self.firmware_version = self._version.version

    def _link_ready(self) -> None:
        # Late replies: nothing in a reply names its request, so after a timeout the
        # link sends ``v`` and discards lines up to the version line it answers.
        assert self._version is not None
        line = f"{self._version.name}:{self._version.version}".encode("ascii")
        self._link.set_resync_line(lambda: (codec.VERSION_QUERY, line))

    async def execute_string_command(self, command: str) -> str:
        """Send ``command`` as it is (no terminator) and return the first reply line.

        As sr-robot3's ``command()``: the firmware answers one line per command byte, so
        a command of several letters gets several lines; the rest are discarded before
        the next request. (Shortly after a request timed out, while its reply may still
        come, such a command raises :class:`~j5aio.errors.CommunicationError` instead:
        its extra lines cannot be told from the late reply.) Using a raw command may
        leave pins in modes the backend does not know of.

        :raises UnexpectedReplyError: the reply is not UTF-8 text.
        :raises CommunicationError: no reply line came in time.
        """
        request = command.encode("utf-8")

        def decode(line: bytes) -> str:
            try:
                return line.decode("utf-8")
            except UnicodeDecodeError:
                raise UnexpectedReplyError("the reply is not UTF-8 text") from None

        return await self._ask(request, decode)
