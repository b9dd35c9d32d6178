"""The simulated KCH: gpiozero's mock pins standing in for the Raspberry Pi's GPIO.

The KCH has no firmware and no wire protocol: it is LEDs on GPIO pins
(:doc:`/internals/kch`).
Its simulator is therefore a set of mock pins, not a byte stream. The simulated KCH board
is the real :class:`~j5aio.backends.hardware.sr.kch.KCHHardwareBackend` driving these pins
through gpiozero's ``MockFactory``, so what a program does to the LEDs goes through the
same code as on a robot, and this object shows what the LEDs show::

    simulator = KCHSimulator()
    kch = simulator.board("SIMKCH")            # a KCHBoard, ready to set up
    await kch.leds[0].set_colour(Colour.CYAN)
    simulator.colours[0]                        # (False, True, True)

Pins are BCM numbers: START 9; A 24/10/25, B 27/23/22, C 4/18/17 (red/green/blue), all
active high. An LED is lit only while its pin is driven high: once the board is closed
(as at the end of a program) gpiozero releases the pins, which on a Raspberry Pi makes
them inputs (lgpio's and RPi.GPIO's pin factories both do), so the LEDs go dark; a
released mock pin is shown dark here too, whatever level it was left at. The pin
numbers are written here from the protocol description, not taken from the backend.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise
from typing import Any, Final, cast

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.kch import KCHHardwareBackend
from j5aio.boards.board import Board

__all__ = ["KCHSimulatedBackend", "KCHSimulator"]

_START: Final = 9
_USER_LEDS: Final = ((24, 10, 25), (27, 23, 22), (4, 18, 17))


class KCHSimulator:
    """A KCH's LEDs on mock GPIO pins, with their state readable.

    :param pin_factory: a gpiozero ``MockFactory`` to use; a new one by default.
    :param serial_number: the asset code the KCH's board gets by default.
    """

    def __init__(self, pin_factory: Any = None, *, serial_number: str = "SIMKCH") -> None:
        self.serial_number = serial_number
        if pin_factory is None:
            from gpiozero.pins.mock import MockFactory

            pin_factory = MockFactory()
        self._factory = pin_factory
        self._board: Board | None = None

    @property
    def pin_factory(self) -> Any:
        """The gpiozero mock pin factory whose pins are the KCH's."""
        return self._factory

    def board(
        self,
        serial_number: str | None = None,
        *,
        backend_class: type[KCHHardwareBackend] | None = None,
    ) -> Board:
        """Return the KCH board driven by the real hardware backend over these pins.

        The pins can be held by one backend at a time, so while the board is open this
        gives back the same board (as discovering a real KCH twice does); once it is
        closed, a new one.

        :param serial_number: the KCH's asset code (for a new board);
            this simulator's ``serial_number`` by default.
        :param backend_class: the backend to drive it with (for a new board), a subclass
            of :class:`~j5aio.backends.hardware.sr.kch.KCHHardwareBackend` such as a
            simulated environment's; that class itself by default.
        """
        board = self._board
        if board is not None and not cast(KCHHardwareBackend, board.backend).closed:
            return board
        backend = backend_class or KCHHardwareBackend
        self._board = backend.from_pin_factory(
            self._factory, self.serial_number if serial_number is None else serial_number,
        )
        return self._board

    def _level(self, pin: int) -> bool:
        """Whether ``pin`` lights its LED: driven (an output) and high."""
        mock = self._factory.pin(pin)
        return mock.function == "output" and bool(mock.state)

    @property
    def colours(self) -> tuple[tuple[bool, bool, bool], ...]:
        """User LEDs A, B and C, each as whether its (red, green, blue) parts are lit.

        Every part is dark once the board has been closed: its pins are no longer driven.
        """
        return tuple(
            (self._level(red), self._level(green), self._level(blue))
            for red, green, blue in _USER_LEDS
        )

    @property
    def start_led(self) -> bool:
        """Whether the start LED is lit at this moment."""
        return self._level(_START)

    @property
    def start_led_changes(self) -> int:
        """How many times the start LED's pin has changed level (it flashes if this grows)."""
        states = self._factory.pin(_START).states
        return sum(1 for before, after in pairwise(states) if before.state != after.state)


class KCHSimulatedBackend(KCHHardwareBackend):
    """The KCH backend of the simulated environment: it finds the current kit's KCH.

    The board is driven by the real :class:`~j5aio.backends.hardware.sr.kch.KCHHardwareBackend` code
    over the simulated KCH's mock pins.
    """

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Return the KCH of the current simulated kit (none if the kit has none).

        :param options: ignored, as by :meth:`.KCHHardwareBackend.discover`.
        """
        from j5aio.simulator.kit import current_kit

        return [
            simulator.board(backend_class=cls)
            for simulator in current_kit().simulators("kch")
            if isinstance(simulator, KCHSimulator)
        ]
