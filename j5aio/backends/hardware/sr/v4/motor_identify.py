r"""Tell an SR v4 motor board's firmware 3 from its firmware 4 by what the board answers.

Both firmwares sit behind the same FTDI adapter (``0403:6001``, "Student Robotics" /
"MCV4B"). Firmware 3 speaks a binary protocol at 1 Mbaud; firmware 4.4 / 4.5 a text
protocol at 115 200 baud. :func:`identify_motor_board` probes an open stream:

1. it sends ``\x00\n*IDN?\n``. Firmware 4 answers the line ``\x00`` with a NACK, then
   its identity. Firmware 3 takes ``0x00`` as a resync (or as an ignored speed byte, if a
   host died half way through a motor command) and ignores the rest: no motor moves,
   and it says nothing;
2. if nothing came, it sends ``\x00\x01``, firmware 3's version query, answered
   ``MCV4B:<version>``.

The probe only works at the baud rate the firmware listens at: open the port at
115 200 baud to find firmware 4, and at 1 000 000 baud to find firmware 3.
"""

from __future__ import annotations

import j5aio.backends.hardware.sr.v4.motor_fw3_codec as fw3
import j5aio.backends.hardware.sr.v4.motor_fw4_codec as fw4
from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.hardware.transports.readers import read_line, read_lines_until
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.errors import CommunicationError, CommunicationTimeoutError

__all__ = ["MotorBoardIdentity", "identify_motor_board", "probe_fw4_identity"]

_BOARD = "SR v4 Motor Board"


def _not_a_nack(line: bytes) -> bool:
    return not line.startswith(b"NACK:")


_FW4_PROBE_REPLY = read_lines_until(_not_a_nack, max_lines=3, max_length=128)
_FW3_VERSION = read_line(max_length=64)


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class MotorBoardIdentity(FrozenRecord):
    """Which firmware a motor board runs, as it said."""

    generation: int
    """3 (binary protocol) or 4 (text protocol)."""
    version: str
    """The version the board reported (``"3"``, ``"4.4.1"``, ``"4.5.0"``...)."""
    asset_tag: str | None
    """The asset tag from ``*IDN?`` (firmware 4 only)."""

    def __init__(self, generation: int, version: str, asset_tag: str | None) -> None:
        set_field = object.__setattr__
        set_field(self, "generation", generation)
        set_field(self, "version", version)
        set_field(self, "asset_tag", asset_tag)


async def probe_fw4_identity(link: SerialLink, *, board: str = _BOARD) -> MotorBoardIdentity:
    """Send the firmware 4 probe on ``link`` and return the identity it answers with.

    :raises CommunicationTimeoutError: nothing answered (firmware 3, or no board).
    :raises UnexpectedReplyError: something answered that is not a firmware 4 motor board.
    """
    lines = await link.exchange(fw4.IDENTIFY_PROBE, _FW4_PROBE_REPLY)
    identity = fw4.parse_identity_reply(board, lines[-1])
    return MotorBoardIdentity(4, identity.version, identity.asset_tag)


async def identify_motor_board(
    stream: ByteStream,
    *,
    port: str | None = None,
    timeout: float = 0.25,
) -> MotorBoardIdentity:
    """Return which firmware the motor board on ``stream`` runs, by what it answers.

    The stream stays open, with nothing left unread: hand it to the matching backend's
    ``from_stream`` (:class:`~.motor_board_fw4.SRV4MotorBoardFw4HardwareBackend` or
    :class:`~.motor_board.SRV4MotorBoardHardwareBackend`).

    :param stream: an open stream to the board.
    :param port: the port's name, for errors; the stream's name by default.
    :param timeout: how long to wait for each answer, in seconds.
    :raises CommunicationError: neither firmware answered (wrong baud rate, or no board),
        or the board's answer is not a motor board's.
    """
    link = SerialLink(stream, name=port, default_timeout=timeout)
    try:
        return await probe_fw4_identity(link)
    except CommunicationTimeoutError:
        pass
    try:
        line = await link.exchange(fw3.RESYNC_AND_VERSION_QUERY, _FW3_VERSION)
    except CommunicationTimeoutError:
        raise CommunicationError(
            f"no SR v4 motor board answered on {link.name}: neither firmware 4 ('*IDN?') "
            "nor firmware 3 (version query). Check the board's power, and the baud rate "
            "(115200 for firmware 4, 1000000 for firmware 3).",
        ) from None
    return MotorBoardIdentity(3, fw3.parse_version_reply(line), None)
