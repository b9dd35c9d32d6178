r"""The hardware backend of the SourceBots Arduino running the sb2024 firmware (``2.0``).

Handshake: the board reboots when the port opens and prints no banner, so ``*IDN?\n`` is
sent and re-sent while there is no answer, or a NACK (the first bytes may reach the
sketch half way through a line), for at most 26 attempts of 1.25 s each, times the time
scale. The reply must be ``SourceBots:Arduino:<asset>:2.0``. The pins' initial modes are
then applied by the board's ``setup()``.

Late replies: nothing in a reply names its request, so after a request timed out (its
reply may still come) the link sends ``*STATUS?`` before the next request and discards
every line up to the ``Yes`` that answers it (only that query is answered so; the
identity query is not used, since late answers to the handshake's own ``*IDN?`` could
be taken for its answer).
"""

from __future__ import annotations

from typing import ClassVar

import j5aio.backends.hardware.sb.arduino_2024_codec as codec
from j5aio.backends.hardware.arduino_gpio import ArduinoGPIOBackend, PinCodec
from j5aio.backends.hardware.serial_backend import scaled
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sb.arduino_2024 import SBArduino2024Board
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)

__all__ = ["SBArduino2024HardwareBackend"]

_LINE = read_line()


class SBArduino2024HardwareBackend(ArduinoGPIOBackend[SBArduino2024Board]):
    """Drives a SourceBots Arduino over the sb2024 colon protocol."""

    board = SBArduino2024Board
    CODEC: ClassVar[PinCodec] = codec

    @classmethod
    async def identify_firmware(
        cls, link: SerialLink, *, time_scale: float = 1.0, attempts: int | None = None,
    ) -> str:
        """Send ``*IDN?`` until the board answers; return its version (``2.0``).

        :raises UnsupportedFirmwareError: a SourceBots Arduino with another version.
        :raises UnexpectedReplyError: the board answered, but not as a SourceBots Arduino.
        :raises CommunicationTimeoutError: no answer after every attempt.
        """
        wait = scaled(cls.DEFAULT_TIMEOUT, time_scale)
        last: CommunicationError | None = None
        for _ in range(cls.IDENTIFY_ATTEMPTS if attempts is None else attempts):
            try:
                line = await link.exchange(codec.IDENTIFY, _LINE, timeout=wait)
                identity = codec.parse_identity(line)
            except (CommunicationTimeoutError, UnexpectedReplyError) as exc:
                last = exc  # booting, or a half line ahead of ours: ask again
                continue
            if not identity.is_sb_arduino:
                raise UnexpectedReplyError(
                    f"the board on {link.name} is a {identity.manufacturer} "
                    f"{identity.board_type}, not a {cls.board.name} (it answered {line!r})",
                )
            if identity.version not in codec.SUPPORTED_VERSIONS:
                raise UnsupportedFirmwareError(
                    cls.board.name, identity.version, codec.SUPPORTED_VERSIONS,
                )
            return identity.version
        raise CommunicationTimeoutError(
            f"{cls.board.name} on {link.name} did not identify itself after "
            f"{attempts or cls.IDENTIFY_ATTEMPTS} tries of *IDN? (last: {last}): is it "
            "powered, and does it run the sb2024 firmware?",
        )

    def _link_ready(self) -> None:
        self._link.set_resync_line(lambda: (codec.STATUS, codec.STATUS_REPLY))

    async def read_pin_mode(self, identifier: int) -> GPIOPinMode:
        """Ask the board which digital mode a pin is in (``MODE:GET?``), bypassing the cache.

        ANALOGUE_INPUT is an input on the board, so it reads back as DIGITAL_INPUT.
        """
        self._pins.mode(identifier)
        return await self._ask(codec.encode_mode_query(identifier), codec.parse_mode)
