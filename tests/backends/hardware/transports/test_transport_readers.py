"""Tests of the reply readers."""

from __future__ import annotations

import dataclasses

import pytest

from j5aio.backends.hardware.transports import (
    line_starts_with,
    read_exactly,
    read_line,
    read_lines,
    read_lines_until,
)
from j5aio.backends.hardware.transports.readers import LineReader, LinesUntilReader
from j5aio.errors import UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated
from tests.fresh_interpreter import printed_words


def test_read_line_waits_for_the_terminator() -> None:
    reader = read_line()
    assert reader.parse(b"") is None
    assert reader.parse(b"partial") is None
    assert reader.parse(b"one\ntwo\n") == (b"one", 4)


def test_read_line_strips_crlf_unless_asked_to_keep_ends() -> None:
    assert read_line().parse(b"+ OK\r\nrest") == (b"+ OK", 6)
    assert read_line(keep_ends=True).parse(bytearray(b"+ OK\r\n")) == (b"+ OK\r\n", 6)


def test_read_line_with_another_terminator() -> None:
    reader = read_line(b"\r")
    assert reader.parse(b"abc\r\n") == (b"abc", 4)
    assert "b'\\r'" in reader.describe()


def test_read_line_rejects_overlong_lines() -> None:
    reader = read_line(max_length=8)
    with pytest.raises(UnexpectedReplyError, match="without a line ending"):
        reader.parse(b"123456789")
    with pytest.raises(UnexpectedReplyError, match="a line of 10 bytes"):
        reader.parse(b"123456789\n")
    assert reader.parse(b"1234567\n") == (b"1234567", 8)


def test_readers_validate_their_arguments() -> None:
    with pytest.raises(ValueError, match="terminator"):
        read_line(b"")
    with pytest.raises(ValueError, match="at least 1"):
        read_exactly(0)
    with pytest.raises(ValueError, match="terminator"):
        read_lines_until(bool, terminator=b"")
    with pytest.raises(ValueError, match="max_lines"):
        read_lines_until(bool, max_lines=0)
    with pytest.raises(ValueError, match="prefix"):
        line_starts_with()


def test_read_exactly() -> None:
    reader = read_exactly(3)
    assert reader.parse(b"ab") is None
    assert reader.parse(b"abcd") == (b"abc", 3)
    assert reader.describe() == "3 bytes"


def test_read_lines_until_a_status_line() -> None:
    reader = read_lines_until(line_starts_with(b"+", b"-"))
    reply = b"# R 2\r\n> H\r\n+ OK\r\nnext"
    assert reader.parse(reply[:12]) is None
    assert reader.parse(reply) == ([b"# R 2", b"> H", b"+ OK"], len(reply) - 4)
    assert "line_starts_with" in reader.describe()


def test_read_lines_until_can_keep_line_ends() -> None:
    reader = read_lines_until(lambda line: line == b"end", keep_ends=True)
    assert reader.parse(b"a\r\nend\r\n") == ([b"a\r\n", b"end\r\n"], 8)


def test_read_lines_until_gives_up_after_max_lines() -> None:
    reader = read_lines_until(line_starts_with(b"+"), max_lines=2)
    with pytest.raises(UnexpectedReplyError, match="2 lines"):
        reader.parse(b"> 1\n> 2\n> 3\n+ OK\n")


def test_line_starts_with_names_itself() -> None:
    predicate = line_starts_with(b"+")
    assert predicate(b"+ OK")
    assert not predicate(b"- Error")
    assert "line_starts_with" in predicate.__name__


def test_read_lines_waits_for_all_of_them() -> None:
    reader = read_lines(2)
    assert reader.parse(b"a\r\n") is None
    assert reader.parse(b"a\r\nb\nrest") == ([b"a", b"b"], 5)
    assert read_lines(1, keep_ends=True).parse(b"a\r\n") == ([b"a\r\n"], 3)
    assert "2 lines" in reader.describe()
    with pytest.raises(UnexpectedReplyError):
        read_lines(2, max_length=4).parse(b"ok\nlonger")
    with pytest.raises(ValueError, match="at least 1"):
        read_lines(0)
    with pytest.raises(ValueError, match="must not be empty"):
        read_lines(2, b"")


def test_the_rarer_readers_are_public_dataclasses_of_the_readers_module() -> None:
    from j5aio.backends.hardware.transports import readers

    home = "j5aio.backends.hardware.transports.readers"
    for name in ("ExactReader", "LinesReader", "MatchingReader"):
        cls = getattr(readers, name)
        assert name in readers.__all__
        assert cls.__module__ == home and cls.__qualname__ == name
        assert issubclass(cls, readers.ReplyReader)
        assert dataclasses.is_dataclass(cls)
    lines = readers.read_lines(2)
    assert isinstance(lines, readers.LinesReader)
    assert repr(lines).startswith("LinesReader(count=2, terminator=b")
    assert [field.name for field in dataclasses.fields(lines)][:2] == ["count", "terminator"]
    assert dataclasses.replace(lines, count=3) == readers.read_lines(3)
    with pytest.raises(dataclasses.FrozenInstanceError):
        lines.count = 4  # type: ignore[misc]
    assert readers.matching(lines, bool).correlates is True
    assert "matching" in dir(readers)


def test_importing_the_readers_does_not_make_the_rarer_ones() -> None:
    """A start that reads only lines never pays for the rarer readers' dataclasses."""
    program = (
        "import sys\n"
        "from j5aio.backends.hardware.transports.readers import read_line, read_lines_until\n"
        "more = 'j5aio.backends.hardware.transports._more_readers'\n"
        "print(more in sys.modules)\n"
        "from j5aio.backends.hardware.transports.readers import LinesReader\n"
        "print(more in sys.modules, LinesReader.__name__)\n"
    )
    assert printed_words(program) == ["False", "True", "LinesReader"]


def test_the_line_readers_are_the_generated_dataclasses() -> None:
    assert_like_generated(
        LineReader, [((), {}), ((b"\r",), {}), ((b"\n", True, 10), {}), ((), {"max_length": 9})]
    )
    until = line_starts_with(b"+")
    assert_like_generated(
        LinesUntilReader,
        [((until,), {}), ((until, b"\r", True, 3, 50), {}), ((bool,), {"max_lines": 1})],
    )
    assert read_line() == read_line() and hash(read_line()) == hash(read_line())
    assert read_lines_until(until) == read_lines_until(until) != read_lines_until(bool)
    with pytest.raises(ValueError, match="max_lines must be at least 1, not 0"):
        LinesUntilReader(until, max_lines=0)
    with pytest.raises(ValueError, match="the line terminator must not be empty"):
        LinesUntilReader(until, terminator=b"")


def test_the_rarer_readers_are_the_generated_dataclasses() -> None:
    from j5aio.backends.hardware.transports.readers import (
        ExactReader,
        LinesReader,
        MatchingReader,
    )

    assert_like_generated(
        LinesReader,
        [((2,), {}), ((3, b"\r", True, 10), {}), ((1,), {"keep_ends": True, "max_length": 9})],
    )
    assert_like_generated(ExactReader, [((1,), {}), ((3,), {}), ((), {"count": 8})])
    line = read_line()
    assert_like_generated(
        MatchingReader,
        [((line, bool), {}), ((read_lines(2), bool, 0), {}), ((line,), {"belongs": bytes.isdigit})],
    )
    # Their checks run however they are made (replace makes a new one too).
    with pytest.raises(ValueError, match="the line count must be at least 1, not 0"):
        dataclasses.replace(LinesReader(2), count=0)
    with pytest.raises(ValueError, match="the line terminator must not be empty"):
        LinesReader(2, terminator=b"")
    with pytest.raises(ValueError, match="the byte count must be at least 1, not -1"):
        ExactReader(-1)
    # A reader made through its subscripted class is the same reader.
    subscripted = MatchingReader[bytes](line, bool)
    assert subscripted == MatchingReader(line, bool) != MatchingReader(line, bytes.isdigit)
    assert subscripted.correlates is True and MatchingReader.correlates is True
    assert hash(read_exactly(3)) == hash(ExactReader(3))
