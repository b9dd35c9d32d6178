"""The safe-state pass: while every board is being made safe, a lost board gets one try.

A board that vanished is looked for again at most once every ``interval`` of its
:class:`~j5aio.backends.hardware.reconnect.ReconnectPolicy` (see
:mod:`j5aio.backends.hardware.reconnect`). When a program ends just after a failed call
(the usual case: the uncaught :class:`~j5aio.errors.BoardDisconnectionError` ends it),
that limit would refuse the orderly stop of a board that has come back, and its motors
would drive on. So :meth:`~j5aio.boards.board.Board.make_all_safe` runs inside
:func:`safe_state_pass`, and within it each lost backend may look for its board once
more, whatever the limit (:func:`claim_attempt`).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["claim_attempt", "making_safe", "safe_state_pass"]

# The ids of the backends that have had their try in the pass running in this context
# (tasks started within it share the set); None outside a pass.
_tried: ContextVar[set[int] | None] = ContextVar("j5aio_safe_state_pass", default=None)


@contextmanager
def safe_state_pass() -> Iterator[None]:
    """Mark the code within (and the tasks it starts) as the pass that makes boards safe."""
    token = _tried.set(set())
    try:
        yield
    finally:
        _tried.reset(token)


def claim_attempt(backend: object) -> bool:
    """Whether ``backend`` may look for its lost board now, regardless of the rate limit.

    True once per backend within a :func:`safe_state_pass`, and never outside one.
    """
    tried = _tried.get()
    if tried is None or id(backend) in tried:
        return False
    tried.add(id(backend))
    return True


def making_safe() -> bool:
    """Whether the code running now is within a :func:`safe_state_pass`."""
    return _tried.get() is not None
