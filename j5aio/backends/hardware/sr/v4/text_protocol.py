r"""What the SR v4 boards' 2023 text firmwares share: one line per command, one per reply.

The power board (fw 4.4), the motor board (fw 4.4 / 4.5) and the servo board (fw 4.3 /
4.4) all take an ASCII command line ending ``\n`` and answer exactly one line: ``ACK``
for an action, data for a query (a command ending ``?``), or ``NACK:<reason>``. They
identify themselves with ``*IDN?`` → ``Student Robotics:<board type>:<asset tag>:<version>``.

These pure functions parse such replies strictly: anything a firmware cannot send is an
:class:`~j5aio.errors.UnexpectedReplyError` naming the board and the reply, and a NACK
is a :class:`~j5aio.errors.CommunicationError` naming the board, the command and the
firmware's reason.
"""

from __future__ import annotations

import itertools
import random
import re
from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import CommunicationError, UnexpectedReplyError

__all__ = [
    "ACK",
    "IDENTIFY",
    "MANUFACTURER",
    "NACK_PREFIX",
    "Identity",
    "NackError",
    "check_ack",
    "check_not_nack",
    "command_line",
    "echo_probe",
    "parse_flag",
    "parse_identity",
    "parse_int",
    "unexpected_reply",
    "version_matches",
]

#: The reply to an action command that worked.
ACK: Final = b"ACK"
#: The identity query, with its line ending.
IDENTIFY: Final = b"*IDN?\n"
#: The manufacturer field of every identity reply.
MANUFACTURER: Final = "Student Robotics"

#: How a refusal starts: ``NACK:<reason>``.
NACK_PREFIX: Final = b"NACK:"
_INTEGER = re.compile(rb"-?[0-9]+")


class NackError(CommunicationError):
    """A board refused a command (it answered ``NACK:<reason>``).

    :param board: the board's name.
    :param command: the command line sent, without its line ending.
    :param reason: the firmware's reason.
    """

    def __init__(self, board: str, command: str, reason: str) -> None:
        self.board = board
        self.command = command
        self.reason = reason
        super().__init__(f"{board} refused the command {command!r}: {reason}")


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: every kit
# with an SR v4 board makes it at start-up, and making the generated ones costs a quarter
# of a millisecond. A test checks them against those.)
@frozen_record
class Identity(FrozenRecord):
    """What a board says in reply to ``*IDN?``."""

    board_type: str
    asset_tag: str
    version: str

    def __init__(self, board_type: str, asset_tag: str, version: str) -> None:
        set_field = object.__setattr__
        set_field(self, "board_type", board_type)
        set_field(self, "asset_tag", asset_tag)
        set_field(self, "version", version)


def command_line(*fields: object) -> bytes:
    r"""Return the command made of ``fields`` joined by ``:``, ending ``\n``."""
    return (":".join(str(field) for field in fields) + "\n").encode("ascii")


#: The start of every resynchronisation nonce: no reply of these firmwares starts so.
_NONCE_PREFIX: Final = "SYNC"
_nonces = itertools.count(random.randrange(0x10000))


def echo_probe() -> tuple[bytes, bytes]:
    r"""Return an ``ECHO`` request with a fresh nonce, and the reply line that answers it.

    ``ECHO:<text>`` changes nothing on the board and is answered by ``<text>`` alone,
    so a link that may have a late reply on its way sends it and discards every line
    up to the nonce (see :meth:`.SerialLink.set_resync_line`). The nonce differs from
    the last 65 535, so even a late answer to an earlier probe is not mistaken for it.

    >>> request, answer = echo_probe()
    >>> request == b"ECHO:" + answer + b"\n"
    True
    """
    nonce = f"{_NONCE_PREFIX}{next(_nonces) % 0x10000:04X}".encode("ascii")
    return b"ECHO:" + nonce + b"\n", nonce


def _shown(command: bytes) -> str:
    return command.rstrip(b"\n").decode("ascii", errors="replace")


def unexpected_reply(
    board: str,
    command: bytes,
    reply: bytes,
    expected: str,
) -> UnexpectedReplyError:
    """Return the error for ``reply`` to ``command``, which should have been ``expected``."""
    return UnexpectedReplyError(
        f"{board} answered {_shown(command)!r} with {reply!r}; expected {expected}",
    )


def check_not_nack(board: str, command: bytes, reply: bytes) -> bytes:
    """Return ``reply`` unless it is a NACK.

    :raises NackError: the reply is ``NACK:<reason>``.
    """
    if reply.startswith(NACK_PREFIX):
        reason = reply[len(NACK_PREFIX) :].decode("ascii", errors="replace")
        raise NackError(board, _shown(command), reason)
    return reply


def check_ack(board: str, command: bytes, reply: bytes) -> None:
    """Check that an action command was acknowledged.

    :raises NackError: the board refused the command.
    :raises UnexpectedReplyError: the reply is neither ``ACK`` nor a NACK.
    """
    if check_not_nack(board, command, reply) != ACK:
        raise unexpected_reply(board, command, reply, "'ACK'")


def parse_int(
    board: str,
    command: bytes,
    reply: bytes,
    *,
    low: int,
    high: int,
) -> int:
    """Return the decimal integer ``reply`` (an optional ``-`` then digits) in ``[low, high]``.

    :raises NackError: the board refused the command.
    :raises UnexpectedReplyError: the reply is not such an integer, or is out of range.
    """
    check_not_nack(board, command, reply)
    if _INTEGER.fullmatch(reply) is None or not low <= int(reply) <= high:
        raise unexpected_reply(board, command, reply, f"an integer from {low} to {high}")
    return int(reply)


def parse_flag(board: str, command: bytes, reply: bytes) -> bool:
    """Return ``True`` for the reply ``1`` and ``False`` for ``0``.

    :raises NackError: the board refused the command.
    :raises UnexpectedReplyError: the reply is anything else.
    """
    check_not_nack(board, command, reply)
    if reply not in (b"0", b"1"):
        raise unexpected_reply(board, command, reply, "'0' or '1'")
    return reply == b"1"


def parse_identity(board: str, reply: bytes, board_type: str) -> Identity:
    """Return the identity in a ``*IDN?`` reply, which must be of ``board_type``.

    :raises UnexpectedReplyError: the reply is not ``Student Robotics:<type>:<asset>:<version>``
        with the expected board type, a printable asset tag and a version.
    """
    try:
        text = reply.decode("ascii")
    except UnicodeDecodeError:
        text = ""
    fields = text.split(":")
    if (
        len(fields) != 4
        or fields[0] != MANUFACTURER
        or fields[1] != board_type
        or not fields[2].isprintable()
        or not fields[3]
        or not fields[3].isprintable()
    ):
        raise UnexpectedReplyError(
            f"expected a {board} to answer '*IDN?' with "
            f"'{MANUFACTURER}:{board_type}:<asset tag>:<version>', got {reply!r}; is this "
            "port really that board?",
        )
    return Identity(fields[1], fields[2], fields[3])


def version_matches(version: str, major_minor: tuple[str, ...]) -> bool:
    """Whether ``version`` is one of ``major_minor`` (``"4.4"``), optionally with ``.<patch>``."""
    head, _, rest = version.partition(".")
    minor, dot, patch = rest.partition(".")
    if f"{head}.{minor}" not in major_minor:
        return False
    return not dot or patch.isdigit()
