from __future__ import annotations

import pytest

from j5aio.service.backoff import Backoff


def test_doubles_to_the_cap_and_resets() -> None:
    backoff = Backoff(0.1, 0.5)
    assert [backoff.next() for _ in range(5)] == [0.1, 0.2, 0.4, 0.5, 0.5]
    backoff.reset()
    assert backoff.next() == 0.1


@pytest.mark.parametrize(("first", "longest"), [(0, 1), (-1, 1), (2, 1)])
def test_bad_delays(first: float, longest: float) -> None:
    with pytest.raises(ValueError, match="first delay"):
        Backoff(first, longest)
