"""Feeding a serial simulator the same bytes whole and in pieces."""

from __future__ import annotations

from hypothesis import strategies as st

from j5aio.simulator.base import SerialBoardSimulator


def pieces(data: bytes, cuts: list[int]) -> list[bytes]:
    """Split ``data`` at the (clamped, sorted) positions in ``cuts``."""
    bounds = sorted({min(max(cut, 0), len(data)) for cut in cuts})
    result: list[bytes] = []
    start = 0
    for bound in bounds:
        result.append(data[start:bound])
        start = bound
    result.append(data[start:])
    return result


def feed(simulator: SerialBoardSimulator, chunks: list[bytes]) -> bytes:
    """Feed each chunk in turn; return everything the simulator emitted."""
    return b"".join(simulator.receive(chunk) for chunk in chunks)


def streams(fragments: list[bytes], max_fragments: int = 30) -> st.SearchStrategy[bytes]:
    """Byte streams made of protocol fragments mixed with arbitrary bytes."""
    fragment = st.one_of(st.sampled_from(fragments), st.binary(max_size=4))
    return st.lists(fragment, max_size=max_fragments).map(b"".join)


cut_lists = st.lists(st.integers(min_value=0, max_value=400), max_size=40)
