"""Assemble received bytes into command lines, the way a line-based firmware does.

A firmware reads one byte at a time into a buffer and acts when the terminator arrives, so
the result never depends on how the bytes were split into writes. Each received byte goes
through these rules, in this order:

1. a byte in ``clear`` empties the buffer (a resync byte);
2. a byte in ``ignore`` is dropped;
3. ``translate`` maps a byte to another (for example TAB to space);
4. the terminator completes the line, which is handed out without the terminator;
5. with ``collapse_spaces``, a space right after a space is dropped. As in the
   SourceBots firmware, "the last byte was a space" is only updated by bytes that reach
   this step (not by cleared, ignored or terminating bytes);
6. anything else is appended.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

__all__ = ["LineAssembler"]

_SPACE = 0x20


class LineAssembler:
    """A byte-at-a-time line buffer with a firmware's input rules."""

    def __init__(
        self,
        *,
        terminator: int = 0x0A,
        clear: bytes = b"",
        ignore: bytes = b"",
        translate: Mapping[int, int] | None = None,
        collapse_spaces: bool = False,
    ) -> None:
        self._terminator = terminator
        self._clear = frozenset(clear)
        self._ignore = frozenset(ignore)
        self._translate = dict(translate or {})
        self._collapse_spaces = collapse_spaces
        self._buffer = bytearray()
        self._after_space = False

    @property
    def pending(self) -> bytes:
        """The partial line received so far."""
        return bytes(self._buffer)

    def reset(self) -> None:
        """Forget everything, as a reboot does."""
        self._buffer.clear()
        self._after_space = False

    def feed(self, data: bytes) -> Iterator[bytes]:
        """Receive ``data``; yield each line it completes, in order, without the terminator."""
        for byte in data:
            if byte in self._clear:
                self._buffer.clear()
                continue
            if byte in self._ignore:
                continue
            byte = self._translate.get(byte, byte)
            if byte == self._terminator:
                line = bytes(self._buffer)
                self._buffer.clear()
                yield line
                continue
            if self._collapse_spaces:
                if byte == _SPACE and self._after_space:
                    continue
                self._after_space = byte == _SPACE
            self._buffer.append(byte)
