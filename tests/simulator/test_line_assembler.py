from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from j5aio.simulator.line_assembler import LineAssembler


def sb_rules() -> LineAssembler:
    return LineAssembler(clear=b"\x00", ignore=b"\r", translate={9: 32}, collapse_spaces=True)


def test_plain_lines_are_split_at_the_terminator() -> None:
    assembler = LineAssembler()
    assert list(assembler.feed(b"one\ntwo\nthr")) == [b"one", b"two"]
    assert assembler.pending == b"thr"
    assert list(assembler.feed(b"ee\n")) == [b"three"]
    assert assembler.pending == b""


def test_spaces_are_kept_without_collapsing() -> None:
    assert list(LineAssembler().feed(b"a  b\t\n")) == [b"a  b\t"]


def test_clear_ignore_translate_and_collapse() -> None:
    assembler = sb_rules()
    assert list(assembler.feed(b"junk\x00W\t\t2 \r  H\n")) == [b"W 2 H"]


def test_empty_line() -> None:
    assert list(sb_rules().feed(b"\n")) == [b""]


def test_space_memory_survives_a_clear_byte_as_in_the_firmware() -> None:
    # After "a " the firmware remembers "last was a space"; NUL clears the buffer but
    # not that flag, so the next space is still dropped.
    assert list(sb_rules().feed(b"a \x00 b\n")) == [b"b"]


def test_space_memory_is_not_touched_by_the_terminator() -> None:
    assert list(sb_rules().feed(b"a \n b\n")) == [b"a ", b"b"]


def test_reset_forgets_the_partial_line_and_the_space_memory() -> None:
    assembler = sb_rules()
    assert list(assembler.feed(b"abc ")) == []
    assembler.reset()
    assert assembler.pending == b""
    assert list(assembler.feed(b" x\n")) == [b" x"]


@given(st.binary(max_size=200), st.lists(st.integers(min_value=0, max_value=200)))
def test_splitting_does_not_change_the_lines(data: bytes, cuts: list[int]) -> None:
    whole = list(sb_rules().feed(data))
    assembler = sb_rules()
    pieces: list[bytes] = []
    start = 0
    for cut in sorted(cuts):
        pieces += assembler.feed(data[start:cut])
        start = max(start, cut)
    pieces += assembler.feed(data[start:])
    assert pieces == whole
