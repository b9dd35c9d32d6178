"""Simulated time: the clocks that board simulators' firmware timers follow.

A board's firmware keeps time: a note on the buzzer ends, a flashing LED toggles, a queue
of notes plays out. A simulator works these out *lazily*: each time its state is read or a
command arrives, it asks its :class:`BoardTime` how long the board has been running, and
brings its timers up to that moment. No thread ticks and nothing costs anything while
nobody looks, yet every reading is current.

Each :class:`BoardTime` follows a :class:`Clock`:

- a simulated kit's boards follow the kit's clock, :func:`kit_clock`: real (monotonic)
  time divided by the kit's time scale, as the robot's own clock
  (:class:`~j5aio.competition.clock.MatchClock`) runs under ``--time-scale``;
- a simulator made on its own follows a :class:`ManualClock`, which stands still until a
  test moves it on, so tests need no sleeps and no timing margins::

      clock = ManualClock()
      board = SRPowerBoardFw4Simulator("SIMPB0")
      board.use_clock(clock)
      ...                       # the host sends NOTE:880:150
      clock.advance(0.2)
      assert board.playing is None

A simulator with timers has ``use_clock(clock)`` (the :class:`ClockedSimulator` shape);
:func:`drive` gives a clock to every such simulator of a collection.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from typing import Final, Protocol, TypeGuard, runtime_checkable

__all__ = [
    "BoardTime",
    "Clock",
    "ClockedSimulator",
    "ManualClock",
    "ScaledClock",
    "drive",
    "kit_clock",
]

_NANOSECONDS: Final = 1_000_000_000


class Clock(Protocol):
    """Anything that tells simulated time."""

    def now(self) -> float:
        """Simulated seconds since an origin of the clock's choosing; never goes back."""
        ...  # pragma: no cover - a protocol


@runtime_checkable
class ClockedSimulator(Protocol):
    """A simulator whose firmware keeps time, and so follows a clock."""

    @property
    def clock(self) -> Clock:
        """The clock the firmware's timers follow."""
        ...  # pragma: no cover - a protocol

    def use_clock(self, clock: Clock) -> None:
        """Follow ``clock`` from now on, keeping the time the board has run so far."""
        ...  # pragma: no cover - a protocol


def _check_seconds(value: object, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"{what} must be a number of seconds, not {type(value).__name__}")
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"{what} must be a finite number of seconds, 0 or more, not {value}")
    return float(value)


class ScaledClock:
    """Real (monotonic) time divided by a time scale.

    :param time_scale: real seconds per simulated second (``2`` runs at half speed).
    :param source: where real time comes from (``time.monotonic`` by default).
    :raises TypeError: ``time_scale`` is not a number.
    :raises ValueError: ``time_scale`` is not more than 0, or not finite.
    """

    def __init__(
        self, time_scale: float = 1.0, *, source: Callable[[], float] = time.monotonic
    ) -> None:
        scale = _check_seconds(time_scale, "time_scale")
        if scale == 0:
            raise ValueError("time_scale must be more than 0: time would stand still")
        self._scale = scale
        self._source = source
        self._origin = source()

    @property
    def time_scale(self) -> float:
        """Real seconds per simulated second."""
        return self._scale

    def now(self) -> float:
        """Simulated seconds since the clock was made."""
        return (self._source() - self._origin) / self._scale

    def __repr__(self) -> str:
        return f"<ScaledClock x{self._scale:g}>"


def kit_clock(time_scale: float) -> ScaledClock:
    """The clock of a simulated kit with this time scale.

    A kit's time scale multiplies the boards' delays, as ``--time-scale`` does the robot's
    seconds, so the kit's clock runs at ``1 / time_scale`` of real time. A scale of ``0``
    (a kit whose boards boot at once, the default) keeps the clock at real time: booting
    is instant, but a 0.15 s note still lasts 0.15 s.

    :raises TypeError: ``time_scale`` is not a number.
    :raises ValueError: ``time_scale`` is negative or not finite.
    """
    scale = _check_seconds(time_scale, "time_scale")
    return ScaledClock(scale or 1.0)


class ManualClock:
    """A clock that stands still until :meth:`advance` moves it on (for tests).

    :param start: the time it shows at first, in seconds.
    """

    def __init__(self, start: float = 0.0) -> None:
        self._now = _check_seconds(start, "start")

    def now(self) -> float:
        """The time the clock shows."""
        return self._now

    def advance(self, seconds: float) -> None:
        """Move the clock on by ``seconds``.

        :raises TypeError: ``seconds`` is not a number.
        :raises ValueError: ``seconds`` is negative or not finite (time only runs forwards).
        """
        self._now += _check_seconds(seconds, "the time to advance")

    def __repr__(self) -> str:
        return f"<ManualClock at {self._now:g} s>"


class BoardTime:
    """How long one board has been running, following a clock that may be swapped.

    Kept in whole nanoseconds, so that times added up (0.1 s three times) compare
    exactly with a timer's end. Swapping the clock (:meth:`follow`) neither loses nor
    adds time: the board's time goes on from where it was.

    :param clock: the clock to follow; a new :class:`ManualClock` by default.
    """

    def __init__(self, clock: Clock | None = None) -> None:
        self._clock: Clock = clock if clock is not None else ManualClock()
        self._seen = self._reading()
        self._elapsed = 0

    def _reading(self) -> int:
        return round(self._clock.now() * _NANOSECONDS)

    @property
    def clock(self) -> Clock:
        """The clock followed now."""
        return self._clock

    def follow(self, clock: Clock) -> None:
        """Follow ``clock`` from now on, keeping the time run so far."""
        self._catch_up()
        self._clock = clock
        self._seen = self._reading()

    def skip(self, seconds: float) -> None:
        """Let ``seconds`` pass on this board beside what its clock tells.

        :raises TypeError: ``seconds`` is not a number.
        :raises ValueError: ``seconds`` is negative or not finite.
        """
        self._elapsed += round(_check_seconds(seconds, "the time to pass") * _NANOSECONDS)

    def _catch_up(self) -> int:
        reading = self._reading()
        if reading > self._seen:  # a clock never goes back; a stray one is ignored
            self._elapsed += reading - self._seen
            self._seen = reading
        return self._elapsed

    def seconds(self) -> float:
        """The board's running time, in seconds."""
        return self._catch_up() / _NANOSECONDS

    def milliseconds(self) -> int:
        """The board's running time, in whole milliseconds (as a firmware's tick counts)."""
        return self._catch_up() // 1_000_000


def _keeps_time(simulator: object) -> TypeGuard[ClockedSimulator]:
    """``isinstance(simulator, ClockedSimulator)``, without its cost.

    (A runtime-checkable protocol lists its members again at every check: some tens of
    microseconds, at each kit's start.) The same test: each member is there, and a
    method's is not ``None``.
    """
    return hasattr(simulator, "clock") and getattr(simulator, "use_clock", None) is not None


def drive(simulators: Iterable[object], clock: Clock) -> None:
    """Make every simulator in ``simulators`` that keeps time follow ``clock``.

    Simulators without timers (those without ``use_clock``) are left alone.
    """
    for simulator in simulators:
        if _keeps_time(simulator):
            simulator.use_clock(clock)
