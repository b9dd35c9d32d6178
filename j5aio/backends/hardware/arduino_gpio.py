"""The base of the Arduino backends whose firmware makes every pin digital (SR fw 2, SB sb2024).

Pins 2 to 19 take the digital modes, A0 to A5 are analogue inputs too, pin 13 is the LED,
and an ultrasound sensor can sit on any two pins. Subclasses give their firmware's codec
(:class:`PinCodec`) and how the board is identified; this class applies the pin rules of
:mod:`~j5aio.backends.hardware.arduino_pins` and keeps the cache right:

* a call is checked before anything is sent (bad input sends nothing);
* the cache changes only after the board has answered, so a call that fails or is
  cancelled never leaves the cache describing what the board was not told;
* every cached fact lives in :attr:`ArduinoGPIOBackend.pins`, and
  :meth:`ArduinoGPIOBackend.forget_board_state` resets it (for a board that rebooted).
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Callable
from typing import Any, ClassVar, Protocol, TypeVar

from j5aio._timedelta import timedelta
from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.backends.backend import BoardT
from j5aio.backends.hardware.arduino import ARDUINO_USB_IDS, UnoLEDAndLimits
from j5aio.backends.hardware.arduino_pins import ArduinoPins, wire_mode
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports.readers import ReplyReader, read_line, read_lines
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.components.derived.ultrasound import UltrasoundInterface
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    CommunicationTimeoutError,
    UnexpectedReplyError,
)

__all__ = ["ArduinoGPIOBackend", "PinCodec", "echo_distance", "echo_pulse"]

T = TypeVar("T")

_LINE = read_line()
_TWO_LINES = read_lines(2)
#: Microseconds of echo per millimetre in both firmwares' formula, mm = 5 x µs / 29.
_US_PER_MM = 29 / 5


def echo_distance(millimetres: int) -> float | None:
    """Return a firmware's ultrasound reading in metres; ``None`` for 0 or less (no echo)."""
    return millimetres / 1000 if millimetres > 0 else None


def echo_pulse(millimetres: int) -> timedelta | None:
    """Return the echo time a reading stands for (``mm x 29 / 5`` µs); ``None`` for no echo.

    These firmwares report only millimetres, so the pulse is worked back from them.
    """
    if millimetres <= 0:
        return None
    return timedelta(microseconds=millimetres * _US_PER_MM)


class PinCodec(Protocol):
    """What this base needs of a firmware's codec module (its functions, by these names)."""

    def encode_mode(self, pin: int, mode: GPIOPinMode) -> bytes:
        """The request that puts ``pin`` in a digital mode."""

    def encode_digital_write(self, pin: int, level: bool) -> bytes:
        """The request that sets the output latch of ``pin``."""

    def encode_digital_read(self, pin: int) -> bytes:
        """The request that reads the level of ``pin``."""

    def encode_analogue_read(self, pin: int) -> bytes:
        """The request that reads the ADC on analogue ``pin``."""

    def encode_ultrasound(self, trigger: int, echo: int) -> bytes:
        """The request that measures with an ultrasound sensor."""

    def parse_done(self, line: bytes) -> None:
        """Check the reply of a mode change or a write."""

    def parse_digital(self, line: bytes) -> bool:
        """Parse the reply of a digital read."""

    def parse_analogue(self, line: bytes) -> float:
        """Parse the reply of an analogue read, in volts."""

    def parse_ultrasound(self, line: bytes) -> int:
        """Parse the reply of an ultrasound measurement, in mm (0 or less: no echo)."""


class ArduinoGPIOBackend(UnoLEDAndLimits, UltrasoundInterface, SerialHardwareBackend[BoardT]):
    """Pins 2-19, LED 0 (pin 13) and ultrasound on an Arduino Uno whose pins are all digital."""

    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = ARDUINO_USB_IDS
    DEFAULT_TIMEOUT: ClassVar[float] = 1.25
    SKIP_PORTS_WITHOUT_SERIAL: ClassVar[bool] = True
    #: How many times the identity query is sent while the board boots (each waits
    #: ``DEFAULT_TIMEOUT`` times the time scale): about 33 s in all, as j5 allowed.
    IDENTIFY_ATTEMPTS: ClassVar[int] = 26
    #: Identification (``attach``, shared-port discovery) scales the waits by this much:
    #: the attempts then span about 5 s, still longer than the Uno's boot, so that a
    #: board of another kind that never answers costs seconds, not half a minute.
    IDENTIFY_TIME_SCALE: ClassVar[float] = 0.15
    #: The firmware's codec module.
    CODEC: ClassVar[PinCodec]

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._pins = ArduinoPins(self.board.name, analogue_mode_required=True)

    @property
    def pins(self) -> ArduinoPins:
        """What the backend remembers of the pins: its only cached board state."""
        return self._pins

    def forget_board_state(self) -> None:
        """Forget the cached pin modes and levels: the board has rebooted (power-on state)."""
        self._pins.reset()

    def reset_board_state(self) -> None:
        """The reconnection hook: a board that came back has rebooted, so forget the pins."""
        self.forget_board_state()

    # -- what a firmware implements -----------------------------------------------------

    @classmethod
    @abstractmethod
    async def identify_firmware(
        cls, link: SerialLink, *, time_scale: float = 1.0, attempts: int | None = None,
    ) -> str:
        """Ask the board on ``link`` who it is; return its version if this backend drives it.

        The query is repeated while the board boots (up to ``attempts`` times,
        :attr:`IDENTIFY_ATTEMPTS` by default).

        :raises UnsupportedFirmwareError: the board runs this firmware, another version.
        :raises CommunicationError: the board never answered as this firmware does.
        """

    # -- helpers for subclasses ---------------------------------------------------------

    async def _handshake(self, *, time_scale: float) -> None:
        self.firmware_version = await self.identify_firmware(self._link, time_scale=time_scale)

    async def _send_mode(
        self, pin: int, mode: GPIOPinMode, *, then: Callable[[], None] | None = None,
    ) -> None:
        """Put ``pin`` in digital ``mode`` (INPUT, INPUT_PULLUP or OUTPUT).

        :param then: runs once the board has confirmed it (update the pin table there).
        """
        await self._tell(self.CODEC.encode_mode(pin, mode), _LINE, then=then)

    async def _send_level(
        self, pin: int, level: bool, *, then: Callable[[], None] | None = None,
    ) -> None:
        """Set the output latch of ``pin`` (drives an output; pull-up of an input).

        :param then: runs once the board has confirmed it (update the pin table there).
        """
        await self._tell(self.CODEC.encode_digital_write(pin, level), _LINE, then=then)

    async def _query_digital(self, pin: int) -> bool:
        return await self._ask(self.CODEC.encode_digital_read(pin), self.CODEC.parse_digital)

    async def _query_analogue(self, pin: int) -> float:
        return await self._ask(self.CODEC.encode_analogue_read(pin), self.CODEC.parse_analogue)

    async def _query_ultrasound(
        self, trigger: int, echo: int, *, then: Callable[[], None] | None = None,
    ) -> int:
        request = self.CODEC.encode_ultrasound(trigger, echo)
        return await self._ask(request, self.CODEC.parse_ultrasound, then=then)

    async def _ask(
        self,
        request: bytes,
        parse: Callable[[bytes], T],
        *,
        then: Callable[[], None] | None = None,
    ) -> T:
        """Send ``request``, read one reply line and parse it.

        ``then`` runs once the reply has arrived and parsed, even for a cancelled caller:
        where the pin table is updated, so that it changes only once the board has been told.

        :raises UnexpectedReplyError: the reply does not parse; the message names the
            board, its port, the request and the reply.
        :raises CommunicationTimeoutError: no reply in time; the message names the board.
        """
        def finish(line: bytes) -> T:
            try:
                value = parse(line)
            except UnexpectedReplyError as exc:
                raise UnexpectedReplyError(
                    f"{self.board.name} on {self.port}: bad reply {line!r} to {request!r}: "
                    f"{exc}",
                ) from exc
            if then is not None:
                then()
            return value

        try:
            return await self.exchange(request, _LINE, then=finish)
        except CommunicationTimeoutError as exc:
            raise CommunicationTimeoutError(f"{self.board.name} did not answer: {exc}") from exc

    # -- pins ---------------------------------------------------------------------------

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        """Put a pin in ``pin_mode``; an output starts at the level last written to it.

        The level is set before the pin becomes an output, so it never glitches. Both
        requests go as one exchange, which the link runs to its end: a cancelled caller
        never leaves the level written (an input's pull-up switched) and the mode not.
        """
        self._pins.check_mode(identifier, pin_mode)
        remember = lambda: self._pins.record(identifier, mode=pin_mode)  # noqa: E731
        # A mode change always waits for the board's acknowledgement (even where commands
        # are confirmed later): the mode remembered is what the pin's other calls check.
        with acknowledge_later(False):
            if pin_mode is not GPIOPinMode.DIGITAL_OUTPUT:
                await self._send_mode(identifier, wire_mode(pin_mode), then=remember)
                return
            level = self.CODEC.encode_digital_write(
                identifier, self._pins.state(identifier).level
            )
            mode = self.CODEC.encode_mode(identifier, wire_mode(pin_mode))
            await self._tell(level + mode, _TWO_LINES, then=remember, requests=(level, mode))

    async def _tell(
        self,
        request: bytes,
        reader: ReplyReader[Any],
        *,
        then: Callable[[], None] | None,
        requests: tuple[bytes, ...] | None = None,
    ) -> None:
        """Send ``request`` (``requests`` joined, if given) and check each acknowledgement.

        The reply carries no value, so inside
        :func:`~j5aio.backends.acknowledgements.acknowledge_later` this returns once the
        bytes are written, and the replies are checked before the board's next request.
        ``then`` runs once every reply has been checked (update the pin table there).

        :raises UnexpectedReplyError: a reply is not an acknowledgement; the message
            names the board, its port, the request and the reply.
        :raises CommunicationTimeoutError: no reply in time; the message names the board.
        """
        sent = requests if requests is not None else (request,)

        def check(reply: bytes | list[bytes]) -> None:
            lines = reply if isinstance(reply, list) else [reply]
            for each, line in zip(sent, lines, strict=True):
                try:
                    self.CODEC.parse_done(line)
                except UnexpectedReplyError as exc:
                    raise UnexpectedReplyError(
                        f"{self.board.name} on {self.port}: bad reply {line!r} to "
                        f"{each!r}: {exc}",
                    ) from exc
            if then is not None:
                then()

        try:
            await self.command(request, reader, then=check)
        except CommunicationTimeoutError as exc:
            raise CommunicationTimeoutError(f"{self.board.name} did not answer: {exc}") from exc

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        """Return the mode last set on a pin."""
        return self._pins.mode(identifier)

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        """Drive an output pin high or low."""
        self._pins.output(identifier, "write to it")
        await self._send_level(
            identifier, state, then=lambda: self._pins.record(identifier, level=state),
        )

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Return the level last written to an output pin."""
        return self._pins.output(identifier, "read back its last written level").level

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Read the level of an input pin."""
        self._pins.check_input(identifier)
        return await self._query_digital(identifier)

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        """Read the voltage on an analogue pin (A0-A5 in ANALOGUE_INPUT mode), in volts."""
        self._pins.check_analogue(identifier)
        return await self._query_analogue(identifier)

    # -- ultrasound ---------------------------------------------------------------------

    async def _measure(self, trigger: int, echo: int) -> int:
        """Measure, then remember the modes the firmware left: trigger low output, echo input."""
        self._pins.mode(trigger)
        self._pins.mode(echo)

        def remember() -> None:
            self._pins.record(trigger, mode=GPIOPinMode.DIGITAL_OUTPUT, level=False)
            self._pins.record(echo, mode=GPIOPinMode.DIGITAL_INPUT)

        return await self._query_ultrasound(trigger, echo, then=remember)

    async def get_ultrasound_pulse(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> timedelta | None:
        """Return the echo time of an ultrasound sensor, or ``None`` with no echo."""
        return echo_pulse(await self._measure(trigger_pin_identifier, echo_pin_identifier))

    async def get_ultrasound_distance(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> float | None:
        """Return the distance in metres, or ``None`` with no echo (never negative)."""
        return echo_distance(await self._measure(trigger_pin_identifier, echo_pin_identifier))
