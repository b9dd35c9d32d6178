"""How long to wait between attempts to reach the broker."""

from __future__ import annotations

from typing import Final

__all__ = ["Backoff"]


class Backoff:
    """Delays that double from ``first`` up to ``longest``, until :meth:`reset`.

    The longest delay bounds how late the service notices a broker that has come back:
    with the defaults, within a second of its return.

    :param first: the first delay, in seconds (more than 0).
    :param longest: the cap, in seconds (at least ``first``).
    :raises ValueError: the delays are out of range.
    """

    FACTOR: Final = 2.0

    def __init__(self, first: float = 0.05, longest: float = 1.0) -> None:
        if not 0 < first <= longest:
            raise ValueError(
                f"the first delay must be more than 0 and at most the longest, "
                f"not {first!r} and {longest!r}"
            )
        self.first = first
        self.longest = longest
        self._next = first

    def next(self) -> float:
        """The delay to wait now; the one after it is longer, up to the cap."""
        delay = self._next
        self._next = min(self._next * self.FACTOR, self.longest)
        return delay

    def reset(self) -> None:
        """Start again from the first delay (after a success)."""
        self._next = self.first
