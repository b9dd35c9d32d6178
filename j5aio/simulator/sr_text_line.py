r"""The line input of the SR v4 boards' 2023 text firmwares, shared by their simulators.

Each of these firmwares collects received bytes into a fixed buffer until ``\n`` and
discards the buffer when it fills without one. What happens to ``\r`` differs (the power
board cuts the line at the first ``\r``, the motor board drops every ``\r``), so the
caller says which bytes to drop, and cuts the line itself where it needs to.
"""

from __future__ import annotations

from collections.abc import Iterator

from .line_assembler import LineAssembler

__all__ = ["BoundedLineInput"]


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
