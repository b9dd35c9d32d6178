r"""The line input of the SR v4 boards' 2023 text firmwares, shared by their simulators.

Each of these firmwares collects received bytes into a fixed buffer until ``\n`` and
discards the buffer when it fills without one. What happens to ``\r`` differs (the power
and servo boards cut the line at the first ``\r``, the motor board drops every ``\r``),
so the caller says which bytes to drop; :func:`answer_lines` cuts the lines and shares
out the reply buffer as the power and servo boards do.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Final

from .line_assembler import LineAssembler

__all__ = ["LINE_LIMIT", "REPLY_BUFFER", "BoundedLineInput", "answer_lines"]

#: How many bytes without a ``\n`` make these firmwares discard their line buffer.
LINE_LIMIT: Final = 63
#: The bytes of the power and servo boards' reply buffer, which the replies to the lines of
#: one USB packet share.
REPLY_BUFFER: Final = 64


class BoundedLineInput:
    r"""A line buffer that discards itself when ``limit`` bytes arrive without a ``\n``.

    :param limit: the buffer length that makes the firmware discard it.
    :param ignore: bytes dropped as they arrive.
    """

    def __init__(self, limit: int, *, ignore: bytes = b"") -> None:
        self._limit = limit
        self._assembler = LineAssembler(ignore=ignore)

    @property
    def pending(self) -> bytes:
        """The partial line received so far."""
        return self._assembler.pending

    def reset(self) -> None:
        """Forget the partial line, as a reboot does."""
        self._assembler.reset()

    def feed(self, data: bytes) -> Iterator[bytes]:
        r"""Receive ``data``; yield each complete line, without its ``\n``."""
        for byte in data:
            yield from self._assembler.feed(bytes((byte,)))
            if len(self._assembler.pending) >= self._limit:
                self._assembler.reset()


def answer_lines(
    line_input: BoundedLineInput, data: bytes, run: Callable[[bytes], bytes],
) -> bytes:
    r"""The power and servo boards' answer to ``data`` (one USB packet).

    Each line it completes is cut at its first ``\r`` and run; each gets one reply line.
    The replies share one buffer of :data:`REPLY_BUFFER` bytes, so a host that sends
    several commands at once may get them cut.
    """
    replies = bytearray()
    for line in line_input.feed(data):
        replies += run(line.split(b"\r", 1)[0]) + b"\n"
    return bytes(replies[:REPLY_BUFFER])
