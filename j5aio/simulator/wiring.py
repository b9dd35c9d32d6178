"""The power wiring of a simulated kit: which power board output feeds which board.

On the Student Robotics kit the motor boards and the servo board take their 12 V from
the power board's outputs, which are off when the power board starts (only L2, the
brain's, is on). A board whose output is off behaves as the real one does: a motor
board's controller does not answer and its motors coast; a servo board answers but
reports its 12 V missing and moves no servo. The Arduinos and the KCH are powered by
USB and are never fed.

A :class:`KitWiring` joins a power board simulator to the boards it feeds. Each time
one of them may have changed (a command from the host, an output switched) and what the
wiring follows did change (an output on or off, a fed board's power or current), it:

- powers each fed board from its output (:attr:`PowerFed.powered`);
- tells the power board what each output supplies (the sum of
  :meth:`PowerFed.supply_current` of the boards on it), so that output currents, the
  battery current and the sagging battery voltage follow what the motors and servos
  draw (the figures are in :mod:`j5aio.simulator.loads`);
- trips and latches an output whose current is over its limit, and every output when
  the whole board is over its limit, as the firmware does (at once: the firmware's
  short hold-off is not modelled).

Outputs are numbered as on the wire (:mod:`j5aio.power_outputs` has their names).

The default wiring (:func:`default_outputs`) puts motor boards on the high-current
outputs first (H0, H1, then L0, L1, L3) and servo boards on the low-current ones first
(L0, L1, L3, then H0, H1), each board on the first output left free; once every output
feeds a board, boards share them in the same order. L2 is the brain's and feeds no board.
"""

from __future__ import annotations

import functools
import sys
import threading
from collections.abc import Callable, Iterable, Sequence
from typing import ClassVar, Final, Protocol, TypeGuard, runtime_checkable

from j5aio.power_outputs import BRAIN_OUTPUT, OUTPUT_NAMES, output_name

from .loads import BOARD_CURRENT_LIMIT, OUTPUT_CURRENT_LIMITS

__all__ = [
    "KitWiring",
    "PowerBoardSimulator",
    "PowerFed",
    "default_outputs",
    "is_power_board",
    "is_power_fed",
]

_MOTOR_ORDER: Final = (0, 1, 2, 3, 5)
_SERVO_ORDER: Final = (2, 3, 5, 0, 1)
#: How many rounds of "a trip switched an output off" one change may take.
_MAX_ROUNDS: Final = 16
#: The motor boards' simulators (module, class), which the default wiring puts on H first.
_MOTOR_BOARD_SIMULATORS: Final = (
    ("j5aio.simulator.sr_motor_fw3", "SRMotorBoardFw3Simulator"),
    ("j5aio.simulator.sr_motor_fw4", "SRMotorBoardFw4Simulator"),
)


@runtime_checkable
class PowerFed(Protocol):
    """A board simulator that takes its 12 V from a power board output."""

    @property
    def powered(self) -> bool:
        """Whether its 12 V input is on."""

    @powered.setter
    def powered(self, on: bool) -> None: ...

    def supply_current(self) -> float:
        """The amps it draws from its 12 V input now."""

    def listen(self, listener: Callable[[], None]) -> Callable[[], None]:
        """Call ``listener`` whenever it may have changed; return what stops the calls."""


@runtime_checkable
class PowerBoardSimulator(Protocol):
    """What a kit's wiring needs of a power board simulator (firmware 3 and 4 have it)."""

    OUTPUT_COUNT: ClassVar[int]

    @property
    def outputs(self) -> tuple[bool, ...]:
        """Whether each output is on."""

    def set_supplied_current(self, output: int, amps: float) -> None:
        """Set what the boards on ``output`` draw through it."""

    def trip_output(self, output: int) -> None:
        """Switch ``output`` off and latch it off, as an over-current does."""

    def listen(self, listener: Callable[[], None]) -> Callable[[], None]:
        """Call ``listener`` whenever it may have changed; return what stops the calls."""


def _fed_state(fed: PowerFed) -> tuple[bool, float]:
    """What the wiring follows of a fed board: its power, and the current it draws."""
    return fed.powered, fed.supply_current()


def _is_motor_board(simulator: object) -> bool:
    # (each module is looked up, not imported: a simulator of it exists only once it is)
    return any(
        isinstance(simulator, getattr(sys.modules[module], name))
        for module, name in _MOTOR_BOARD_SIMULATORS
        if module in sys.modules
    )


# ``isinstance`` against the protocols above lists their members again at every check
# (some tens of microseconds, each simulator of each kit at its start); these make the
# same test: each member is there, and a method's is not ``None``.


def _has_members(obj: object, data: tuple[str, ...], methods: tuple[str, ...]) -> bool:
    return all(hasattr(obj, name) for name in data) and all(
        getattr(obj, name, None) is not None for name in methods
    )


def is_power_fed(simulator: object) -> TypeGuard[PowerFed]:
    """Whether ``simulator`` has the :class:`PowerFed` shape (as ``isinstance`` says)."""
    return _has_members(simulator, ("powered",), ("supply_current", "listen"))


def is_power_board(simulator: object) -> TypeGuard[PowerBoardSimulator]:
    """Whether ``simulator`` has the :class:`PowerBoardSimulator` shape (as ``isinstance`` says)."""
    return _has_members(
        simulator,
        ("OUTPUT_COUNT", "outputs"),
        ("set_supplied_current", "trip_output", "listen"),
    )


def default_outputs(fed: Sequence[object], *, taken: Iterable[int] = ()) -> list[int]:
    """The outputs the default wiring gives ``fed`` boards, in their order.

    :param fed: the boards to wire (motor boards go on H outputs first, others on L).
    :param taken: outputs already feeding a board, chosen elsewhere.
    """
    used = list(taken)
    chosen: list[int] = []
    for simulator in fed:
        order = _MOTOR_ORDER if _is_motor_board(simulator) else _SERVO_ORDER
        # The first output feeding fewest boards, in this board's order of preference.
        output = min(order, key=lambda out: (used.count(out), order.index(out)))
        used.append(output)
        chosen.append(output)
    return chosen


class KitWiring:
    """Feeds boards from a power board's outputs, and loads the battery with them.

    :param power_board: the power board simulator.
    :param feeds: each fed board with the number of the output feeding it.
    :raises ValueError: an output does not exist on the board, or is L2 (the brain's).
    """

    def __init__(
        self, power_board: PowerBoardSimulator, feeds: Iterable[tuple[PowerFed, int]]
    ) -> None:
        self._power_board = power_board
        self._feeds = tuple(feeds)
        count = power_board.OUTPUT_COUNT
        for simulator, output in self._feeds:
            if not 0 <= output < count:
                raise ValueError(
                    f"{simulator!r} is wired to output {output}, which the power board "
                    f"does not have: it has {', '.join(OUTPUT_NAMES[:count])}"
                )
            if output == BRAIN_OUTPUT:
                raise ValueError(
                    f"{simulator!r} cannot be wired to L2: that output powers the brain"
                )
        self._lock = threading.RLock()
        self._syncing = False
        self._again = False
        # What the wiring follows, as the last update left it: the outputs, and each fed
        # board's power and current. A board's change that leaves its own so needs no
        # update (each board tells of its own changes).
        self._settled_outputs: tuple[bool, ...] | None = None
        self._settled_feeds: list[tuple[bool, float] | None] = [None] * len(self._feeds)
        self._stops: list[Callable[[], None]] = []
        self._stops.append(power_board.listen(self._outputs_may_have_changed))
        for index, (simulator, _) in enumerate(self._feeds):
            self._stops.append(
                simulator.listen(functools.partial(self._fed_may_have_changed, index))
            )
        self.sync()

    @property
    def power_board(self) -> PowerBoardSimulator:
        """The power board whose outputs feed the boards."""
        return self._power_board

    @property
    def feeds(self) -> tuple[tuple[PowerFed, int], ...]:
        """Each fed board with the number of the output feeding it."""
        return self._feeds

    def output_feeding(self, simulator: object) -> int | None:
        """The number of the output feeding ``simulator``, or ``None`` if none does."""
        return next((out for fed, out in self._feeds if fed is simulator), None)

    def output_current(self, output: int) -> float:
        """What the boards on ``output`` draw now, in amps (0 while it is off)."""
        if not self._power_board.outputs[output]:
            return 0.0
        return sum(fed.supply_current() for fed, out in self._feeds if out == output)

    def sync(self) -> None:
        """Bring every fed board's power and the power board's loads up to date.

        Safe to call at any time. A board's change calls it when what the wiring
        follows of that board has changed since the last update: the power board's
        outputs, or a fed board's power or the current it draws (a command that changes
        neither, a reading say, needs no update).
        """
        with self._lock:
            if self._syncing:  # a change made by this very update: go round again
                self._again = True
                return
            self._syncing = True
            self._settled_outputs = None  # (until an update changes nothing more)
            try:
                for _ in range(_MAX_ROUNDS):
                    self._again = False
                    self._update()
                    if not self._again:
                        self._settled_outputs = self._power_board.outputs
                        self._settled_feeds = [_fed_state(fed) for fed, _ in self._feeds]
                        break
            finally:
                self._syncing = False

    def _outputs_may_have_changed(self) -> None:
        """The power board may have changed: update if its outputs did."""
        with self._lock:
            if self._syncing or self._power_board.outputs != self._settled_outputs:
                self.sync()

    def _fed_may_have_changed(self, index: int) -> None:
        """The fed board ``index`` may have changed: update if its power or current did."""
        with self._lock:
            if (
                self._syncing
                or self._settled_outputs is None
                or _fed_state(self._feeds[index][0]) != self._settled_feeds[index]
            ):
                self.sync()

    def _update(self) -> None:
        board = self._power_board
        outputs = board.outputs
        for fed, output in self._feeds:
            if fed.powered != outputs[output]:
                fed.powered = outputs[output]
        # What each output supplies, as output_current says, in one pass over the feeds.
        loads = [0.0] * board.OUTPUT_COUNT
        now_on = board.outputs
        for fed, output in self._feeds:
            if now_on[output]:
                loads[output] += fed.supply_current()
        for output, amps in enumerate(loads):
            board.set_supplied_current(output, amps)
        for output, amps in enumerate(loads):
            if outputs[output] and amps > OUTPUT_CURRENT_LIMITS[output]:
                board.trip_output(output)
        if sum(loads) > BOARD_CURRENT_LIMIT:
            for output, on in enumerate(board.outputs):
                if on and output != BRAIN_OUTPUT:
                    board.trip_output(output)

    def close(self) -> None:
        """Stop following the boards (they keep the power they have)."""
        for stop in self._stops:
            stop()
        self._stops.clear()

    def __repr__(self) -> str:
        wires = ", ".join(
            f"{output_name(out)}: {type(fed).__name__} {getattr(fed, 'serial_number', '?')}"
            for fed, out in self._feeds
        )
        return f"<KitWiring {wires}>"
