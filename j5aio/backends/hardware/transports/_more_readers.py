"""The reply readers a start seldom needs: a fixed count of lines or bytes, correlated replies.

Their public home is :mod:`~j5aio.backends.hardware.transports.readers`, which imports
this module the first time one of its names is used there: the boards of a usual kit
read single lines, so a start never pays for making these dataclasses. Each class says
that home as its module, so that its name, its documentation and the annotations that
name it all point there.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import ClassVar

from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import UnexpectedReplyError

from .readers import (
    DEFAULT_MAX_LINE,
    DEFAULT_MAX_SKIPPED,
    ReplyReader,
    T_co,
    split_line,
    strip_line,
)

__all__ = ["ExactReader", "LinesReader", "MatchingReader", "matching", "read_exactly", "read_lines"]

#: Where these names are documented and looked up (see the module's docstring).
_HOME = "j5aio.backends.hardware.transports.readers"

# These readers write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them (as
# the line readers do): a start that uses one should not pay a third of a millisecond a
# class for making the generated methods. A test checks them against those.


@frozen_record
class LinesReader(ReplyReader[list[bytes]], FrozenRecord):
    """A fixed number of lines; see :func:`read_lines`."""

    __module__ = _HOME

    count: int
    terminator: bytes = b"\n"
    keep_ends: bool = False
    max_length: int = DEFAULT_MAX_LINE

    def __init__(
        self,
        count: int,
        terminator: bytes = b"\n",
        keep_ends: bool = False,
        max_length: int = DEFAULT_MAX_LINE,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "count", count)
        set_field(self, "terminator", terminator)
        set_field(self, "keep_ends", keep_ends)
        set_field(self, "max_length", max_length)
        self.__post_init__()

    def __post_init__(self) -> None:
        if not self.terminator:
            raise ValueError("the line terminator must not be empty")
        if self.count < 1:
            raise ValueError(f"the line count must be at least 1, not {self.count}")

    def parse(self, buffer: bytes | bytearray) -> tuple[list[bytes], int] | None:
        """Return the first ``count`` lines of ``buffer``, once they have all arrived."""
        lines: list[bytes] = []
        position = 0
        while len(lines) < self.count:
            found = split_line(buffer, position, self.terminator, self.max_length)
            if found is None:
                return None
            line, position = found
            lines.append(line if self.keep_ends else strip_line(line, self.terminator))
        return lines, position

    def describe(self) -> str:
        """Describe this reader."""
        return f"{self.count} lines ending {self.terminator!r}"


@frozen_record
class ExactReader(ReplyReader[bytes], FrozenRecord):
    """A fixed number of bytes; see :func:`read_exactly`."""

    __module__ = _HOME

    count: int

    def __init__(self, count: int) -> None:
        object.__setattr__(self, "count", count)
        self.__post_init__()

    def __post_init__(self) -> None:
        if self.count < 1:
            raise ValueError(f"the byte count must be at least 1, not {self.count}")

    def parse(self, buffer: bytes | bytearray) -> tuple[bytes, int] | None:
        """Return the first ``count`` bytes of ``buffer``, once there are enough."""
        if len(buffer) < self.count:
            return None
        return bytes(buffer[: self.count]), self.count

    def describe(self) -> str:
        """Describe this reader."""
        return f"{self.count} bytes"


def read_lines(
    count: int,
    terminator: bytes = b"\n",
    *,
    keep_ends: bool = False,
    max_length: int = DEFAULT_MAX_LINE,
) -> LinesReader:
    """Read ``count`` lines: the replies to as many one-line requests sent together.

    Options as :func:`read_line`. Sending several requests as one exchange makes them one
    unit for cancellation: the link runs an exchange to its end, so a caller cancelled
    between them never leaves the first done and the second not.
    """
    return LinesReader(count, terminator, keep_ends, max_length)


def read_exactly(count: int) -> ExactReader:
    """Read exactly ``count`` bytes."""
    return ExactReader(count)


@frozen_record
class MatchingReader(ReplyReader[T_co], FrozenRecord):
    """Replies of ``reader`` that ``belongs`` accepts; others are skipped whole.

    See :func:`matching`. Its :attr:`~ReplyReader.correlates` is always true: foreign
    replies are recognised and skipped.
    """

    __module__ = _HOME

    reader: ReplyReader[T_co]
    belongs: Callable[[T_co], bool]
    max_skipped: int = DEFAULT_MAX_SKIPPED

    def __init__(
        self,
        reader: ReplyReader[T_co],
        belongs: Callable[[T_co], bool],
        max_skipped: int = DEFAULT_MAX_SKIPPED,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "reader", reader)
        set_field(self, "belongs", belongs)
        set_field(self, "max_skipped", max_skipped)

    def parse(self, buffer: bytes | bytearray) -> tuple[T_co, int] | None:
        """Return the first reply in ``buffer`` that belongs to this request."""
        found = self.parse_counting(buffer)
        return None if found is None else found[:2]

    def parse_counting(self, buffer: bytes | bytearray) -> tuple[T_co, int, int] | None:
        """As :meth:`parse`, and also say how many foreign replies were skipped."""
        position = 0
        for skipped in range(self.max_skipped + 1):
            parsed = self.reader.parse(buffer[position:])
            if parsed is None:
                return None
            reply, used = parsed
            position += used
            if self.belongs(reply):
                return reply, position, skipped
        raise UnexpectedReplyError(
            f"received {self.max_skipped + 1} replies that belong to other requests"
        )

    def describe(self) -> str:
        """Describe this reader."""
        name = getattr(self.belongs, "__name__", repr(self.belongs))
        return f"{self.reader.describe()}, for which {name} holds"

    #: Always true: foreign replies are recognised and skipped.
    correlates: ClassVar[bool] = True


def matching(
    reader: ReplyReader[T_co],
    belongs: Callable[[T_co], bool],
    *,
    max_skipped: int = DEFAULT_MAX_SKIPPED,
) -> MatchingReader[T_co]:
    """Read replies with ``reader``, skipping whole those for which ``belongs`` is false.

    For a firmware that marks each reply with something of its request (an echo, a
    request id): a reply that arrives after its request timed out is then skipped by the
    next request instead of being taken as its answer, whatever its timing.
    """
    return MatchingReader(reader, belongs, max_skipped)
