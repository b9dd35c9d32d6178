r"""Reply readers: how a :class:`~.serial_link.SerialLink` knows a reply has ended.

A reader looks at the bytes received so far and either says "not complete yet" or returns
the parsed reply and how many bytes it used. Readers hold no state, so one instance can
be kept at module level and shared::

    STATUS = read_lines_until(line_starts_with(b"+", b"-"))   # SB Arduino 2019
    reply = await link.exchange(b"R 2\n", STATUS, timeout=1.25)

    line = await link.exchange(b"v", read_line(), timeout=0.5)    # Ruggeduino
    version = await link.exchange(b"\x01", read_line(), timeout=0.25)  # motor fw 3

**Correlation.** A reader that can tell its own reply from a late reply to an earlier
request says so with :attr:`ReplyReader.correlates` (see :func:`matching`): the link
then needs no guess about when the line is quiet, since the reader itself skips whole
replies that belong to other requests.
"""

from __future__ import annotations

import abc
from collections.abc import Callable
from typing import TYPE_CHECKING, ClassVar, Generic, TypeVar

from j5aio._lazy import lazy_exports
from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import UnexpectedReplyError

if TYPE_CHECKING:
    from ._more_readers import ExactReader as ExactReader
    from ._more_readers import LinesReader as LinesReader
    from ._more_readers import MatchingReader as MatchingReader
    from ._more_readers import matching as matching
    from ._more_readers import read_exactly as read_exactly
    from ._more_readers import read_lines as read_lines

__all__ = [
    "ExactReader",
    "LineReader",
    "LinesReader",
    "LinesUntilReader",
    "MatchingReader",
    "ReplyReader",
    "line_starts_with",
    "matching",
    "read_exactly",
    "read_line",
    "read_lines",
    "read_lines_until",
]

T_co = TypeVar("T_co", covariant=True)

#: The longest line readers accept by default, in bytes, terminator included.
DEFAULT_MAX_LINE = 4096


class ReplyReader(abc.ABC, Generic[T_co]):
    """Decides where a reply ends, and parses it."""

    @abc.abstractmethod
    def parse(self, buffer: bytes | bytearray) -> tuple[T_co, int] | None:
        """Parse a reply at the start of ``buffer``.

        :returns: ``(reply, bytes_used)`` if ``buffer`` starts with a complete reply, or
            ``None`` if more bytes are needed.
        :raises UnexpectedReplyError: ``buffer`` cannot start a valid reply (for
            example, a line longer than allowed).
        """

    @abc.abstractmethod
    def describe(self) -> str:
        """Say in a few words what this reader waits for, for error messages."""

    #: Whether this reader recognises, and skips, replies to other requests. False by
    #: default: a reader that only finds where a reply ends cannot tell a late reply to
    #: an earlier request from its own. (A class attribute, read on every exchange; a
    #: subclass may make it a property.)
    correlates: ClassVar[bool] = False


def split_line(
    buffer: bytes | bytearray, start: int, terminator: bytes, max_length: int
) -> tuple[bytes, int] | None:
    """Find the line starting at ``start``: return (line with terminator, end) or None."""
    end = buffer.find(terminator, start)
    if end < 0:
        if len(buffer) - start > max_length:
            raise UnexpectedReplyError(
                f"received {len(buffer) - start} bytes without a line ending "
                f"{terminator!r} (longest line allowed is {max_length} bytes)"
            )
        return None
    end += len(terminator)
    if end - start > max_length:
        raise UnexpectedReplyError(
            f"received a line of {end - start} bytes (longest allowed is {max_length})"
        )
    return bytes(buffer[start:end]), end


def strip_line(line: bytes, terminator: bytes) -> bytes:
    """Remove ``terminator`` from the end of ``line``, and a carriage return before a newline."""
    line = line[: -len(terminator)]
    if terminator == b"\n" and line.endswith(b"\r"):
        line = line[:-1]
    return line


# The two readers every line protocol uses write their own ``__init__`` and take freezing,
# ``__repr__``, ``__eq__`` and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)``
# would make them: every program imports them, and making the generated ones costs a third
# of a millisecond a class. A test checks them against those.


@frozen_record
class LineReader(ReplyReader[bytes], FrozenRecord):
    """One line; see :func:`read_line`."""

    terminator: bytes = b"\n"
    keep_ends: bool = False
    max_length: int = DEFAULT_MAX_LINE

    def __init__(
        self, terminator: bytes = b"\n", keep_ends: bool = False, max_length: int = DEFAULT_MAX_LINE
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "terminator", terminator)
        set_field(self, "keep_ends", keep_ends)
        set_field(self, "max_length", max_length)
        self.__post_init__()

    def __post_init__(self) -> None:
        if not self.terminator:
            raise ValueError("the line terminator must not be empty")

    def parse(self, buffer: bytes | bytearray) -> tuple[bytes, int] | None:
        """Return the first line of ``buffer``, if it is complete."""
        # Every reply of a line protocol is read here: the common cases are written out
        # (a line too long is left to split_line, which refuses it).
        terminator = self.terminator
        end = buffer.find(terminator)
        if end < 0:
            if len(buffer) <= self.max_length:
                return None
            return split_line(buffer, 0, terminator, self.max_length)
        end += len(terminator)
        if end > self.max_length:
            return split_line(buffer, 0, terminator, self.max_length)
        line = bytes(buffer[:end])
        if not self.keep_ends:
            line = line[: -len(terminator)]
            if terminator == b"\n" and line.endswith(b"\r"):
                line = line[:-1]
        return line, end

    def describe(self) -> str:
        """Describe this reader."""
        return f"a line ending {self.terminator!r}"


@frozen_record
class LinesUntilReader(ReplyReader[list[bytes]], FrozenRecord):
    """Lines up to and including one that satisfies a predicate; see :func:`read_lines_until`."""

    predicate: Callable[[bytes], bool]
    terminator: bytes = b"\n"
    keep_ends: bool = False
    max_lines: int = 64
    max_length: int = DEFAULT_MAX_LINE

    def __init__(
        self,
        predicate: Callable[[bytes], bool],
        terminator: bytes = b"\n",
        keep_ends: bool = False,
        max_lines: int = 64,
        max_length: int = DEFAULT_MAX_LINE,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "predicate", predicate)
        set_field(self, "terminator", terminator)
        set_field(self, "keep_ends", keep_ends)
        set_field(self, "max_lines", max_lines)
        set_field(self, "max_length", max_length)
        self.__post_init__()

    def __post_init__(self) -> None:
        if not self.terminator:
            raise ValueError("the line terminator must not be empty")
        if self.max_lines < 1:
            raise ValueError(f"max_lines must be at least 1, not {self.max_lines}")

    def parse(self, buffer: bytes | bytearray) -> tuple[list[bytes], int] | None:
        """Return the lines of ``buffer`` up to the final one, once it has arrived."""
        lines: list[bytes] = []
        position = 0
        while True:
            found = split_line(buffer, position, self.terminator, self.max_length)
            if found is None:
                return None
            raw, position = found
            stripped = strip_line(raw, self.terminator)
            lines.append(raw if self.keep_ends else stripped)
            if self.predicate(stripped):
                return lines, position
            if len(lines) >= self.max_lines:
                raise UnexpectedReplyError(
                    f"received {len(lines)} lines without the final line of the reply"
                )

    def describe(self) -> str:
        """Describe this reader."""
        name = getattr(self.predicate, "__name__", repr(self.predicate))
        return f"lines ending {self.terminator!r} until one satisfies {name}"


def read_line(
    terminator: bytes = b"\n", *, keep_ends: bool = False, max_length: int = DEFAULT_MAX_LINE
) -> LineReader:
    r"""Read one line.

    :param terminator: the bytes that end the line.
    :param keep_ends: keep the terminator. Without it, the terminator is removed, and
        for ``b"\n"`` a ``b"\r"`` before it too.
    :param max_length: the longest line accepted, terminator included; more bytes
        without a terminator raise :class:`~j5aio.errors.UnexpectedReplyError`.
    """
    return LineReader(terminator, keep_ends, max_length)


def read_lines_until(
    predicate: Callable[[bytes], bool],
    *,
    terminator: bytes = b"\n",
    keep_ends: bool = False,
    max_lines: int = 64,
    max_length: int = DEFAULT_MAX_LINE,
) -> LinesUntilReader:
    r"""Read lines until one satisfies ``predicate``; return them all, that one included.

    ``predicate`` is called with each line without its terminator (and without a
    ``b"\r"`` before a ``b"\n"``). More than ``max_lines`` lines without the final one
    raise :class:`~j5aio.errors.UnexpectedReplyError`.
    """
    return LinesUntilReader(predicate, terminator, keep_ends, max_lines, max_length)


def line_starts_with(*prefixes: bytes) -> Callable[[bytes], bool]:
    """Return a predicate for :func:`read_lines_until`: the line starts with a prefix.

    ``line_starts_with(b"+", b"-")`` finds the status line that ends an SB Arduino
    (2019) reply.
    """
    if not prefixes:
        raise ValueError("give at least one prefix")

    def starts_with_prefix(line: bytes) -> bool:
        return line.startswith(prefixes)

    starts_with_prefix.__name__ = f"line_starts_with{prefixes!r}"
    return starts_with_prefix


#: The most whole foreign replies a :class:`MatchingReader` skips before giving up.
DEFAULT_MAX_SKIPPED = 32

# The readers a start seldom needs (a fixed count of lines or bytes, correlated replies)
# are defined in their own module, imported the first time one of these names is used:
# each frozen dataclass costs a start a few hundred microseconds to make.
if not TYPE_CHECKING:
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.hardware.transports._more_readers": [
                "ExactReader",
                "LinesReader",
                "MatchingReader",
                "matching",
                "read_exactly",
                "read_lines",
            ],
        },
    )
