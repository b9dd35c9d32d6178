"""Acknowledgements confirmed later: a command returns once its bytes have gone.

Many commands get a reply that carries no value, only "done" (the fw 4 boards' ``ACK``,
the Arduinos' acknowledgements). Normally a command waits for that reply, so a program
that drives one board after another waits for each board's answer in turn. Inside
:func:`acknowledge_later`, such a command returns as soon as its bytes are written, and
its acknowledgement is read and checked later, while the program goes on to other boards:

* before that board's next request (each board's link keeps one request outstanding, so
  its replies stay in order, and the late-reply and line-noise recovery work as ever);
* when the board is closed, and when it is made safe at the end of the program.

A refusal or a missing acknowledgement found then is logged at once, and raised by that
board's next request as :class:`~j5aio.errors.EarlierCommandError` naming the earlier
command; the next request is then not sent. What a backend remembers of the board
(its ``then=`` callbacks) changes when the acknowledgement is read, as it always does.

It is off by default: ``await motor.set_power(0.5)`` completes on the board's
acknowledgement. The switch is a ``contextvars.ContextVar``, so it holds in the
context that sets it and in the tasks started from it, and nowhere else::

    with acknowledge_later():
        await motor.set_power(0.5)   # returns once the command is written
        await servo.set_position(0)  # the motor's ACK travels meanwhile
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Final

__all__ = ["LATER_SWITCH", "acknowledge_later", "acknowledging_later"]

_LATER: ContextVar[bool] = ContextVar("j5aio_acknowledge_later", default=False)

#: The context variable that :func:`acknowledge_later` sets: ``LATER_SWITCH.get()`` is
#: :func:`acknowledging_later` read without a call of it, for a link's hot path.
LATER_SWITCH: Final = _LATER


@contextmanager
def acknowledge_later(enabled: bool = True) -> Iterator[None]:
    """Within this block, commands whose reply only acknowledges return once sent.

    See the module's notes for when the acknowledgements are then read and checked.
    Nested blocks restore the setting they found when they end.

    :param enabled: ``False`` turns the switch off within the block (to wait for every
        acknowledgement in one part of a program that otherwise confirms them later).
    """
    token = _LATER.set(bool(enabled))
    try:
        yield
    finally:
        _LATER.reset(token)


def acknowledging_later() -> bool:
    """Whether commands in this context return before their acknowledgement is read."""
    return _LATER.get()
