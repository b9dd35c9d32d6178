"""The base of the Arduino Uno serial backends: pins and the LED, over the shared pin rules.

Subclasses say how a pin's state is sent to the board and how pins are read; this class
applies :mod:`~j5aio.backends.hardware.arduino_pins` so that every Arduino board refuses the same
things with the same errors.

What the backend remembers of a pin changes only once the board has been told: a new
mode or level is sent first, and stored by the subclass when the board has answered
(see ``ArduinoHardwareBackend._apply_pin``), so a cancelled or failed change leaves
the remembered state as it was.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.backends.backend import BoardT
from j5aio.backends.hardware.arduino_pins import LED_PIN, ArduinoPins, DigitalPinState
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.components.gpio_pin import GPIOPinInterface, GPIOPinMode
from j5aio.components.led import LEDInterface
from j5aio.errors import NotSupportedByHardwareError

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = ["ARDUINO_USB_IDS", "ArduinoHardwareBackend", "UnoLEDAndLimits"]

#: Arduino Uno R3 (arduino.cc and arduino.org), CH340 clone, CP210x and Ruggeduino.
ARDUINO_USB_IDS: frozenset[tuple[int, int]] = frozenset(
    {
        (0x2341, 0x0043),
        (0x2A03, 0x0043),
        (0x1A86, 0x7523),
        (0x10C4, 0xEA60),
        (0x16D0, 0x0613),
    },
)


class UnoLEDAndLimits(GPIOPinInterface, LEDInterface):
    """What every Uno backend does alike: LED 0 is pin 13, and there is no DAC or PWM.

    Mixed into both Arduino bases (this module's and
    :class:`~j5aio.backends.hardware.arduino_gpio.ArduinoGPIOBackend`), before the
    backend class that gives ``board``.
    """

    board: ClassVar[type[Board]]

    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        """Refuse: the Uno has no DAC."""
        raise NotSupportedByHardwareError(f"{self.board.name} has no DAC (analogue output)")

    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        """Refuse: the firmware has no PWM command."""
        raise NotSupportedByHardwareError(
            f"{self.board.name}'s firmware has no PWM output command",
        )

    async def get_led_state(self, identifier: int) -> bool:
        """Return the level last written to the LED (pin 13, which must be an output)."""
        ArduinoPins.check_led(identifier, self.board.name)
        return await self.get_gpio_pin_digital_state(LED_PIN)

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or clear the LED (pin 13, which must be an output)."""
        ArduinoPins.check_led(identifier, self.board.name)
        await self.write_gpio_pin_digital_state(LED_PIN, state)


class ArduinoHardwareBackend(UnoLEDAndLimits, SerialHardwareBackend[BoardT]):
    """Pins 2-13 (digital), 14-19 (analogue) and LED 0 (pin 13) of an Arduino Uno."""

    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = ARDUINO_USB_IDS
    DEFAULT_TIMEOUT: ClassVar[float] = 1.25
    SKIP_PORTS_WITHOUT_SERIAL: ClassVar[bool] = True
    #: How many analogue pins the firmware reads, from A0.
    ANALOGUE_CHANNELS: ClassVar[int] = 6
    #: Whether the firmware drives A0 to A5 as digital pins too.
    ANALOGUE_PINS_DIGITAL: ClassVar[bool] = False

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._pins = ArduinoPins(
            self.board.name, analogue_pins_digital=self.ANALOGUE_PINS_DIGITAL,
        )

    def make_safe_now(self, timeout: float) -> bool:
        """Send nothing: like :meth:`.ArduinoUno.make_safe`, pins stay as they are.

        No pin state suits every circuit (an output low may start a pump); see
        :meth:`.Backend.make_safe_now`.
        """
        return False

    @abstractmethod
    async def _apply_pin(
        self, identifier: int, wanted: DigitalPinState, *, mode_changed: bool
    ) -> None:
        """Tell the board to put digital pin ``identifier`` in state ``wanted``.

        Store each part of ``wanted`` in ``self._pins.digital(identifier)`` only once
        the board has been told it (in the link's ``then=`` callback), never before.
        """

    def _remember_pin(self, identifier: int, mode: GPIOPinMode, level: bool) -> None:
        """Store what the board was just told about a digital pin."""
        self._pins.record(identifier, mode=mode, level=level)

    def reset_board_state(self) -> None:
        """Forget what was remembered: the pins are as after power-on (see the pin rules)."""
        self._pins.reset()

    @abstractmethod
    async def _read_digital(self, identifier: int) -> bool:
        """Read the level of digital input ``identifier``."""

    @abstractmethod
    async def _read_analogue(self, identifier: int) -> float:
        """Read the voltage on analogue pin ``identifier``."""

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        """Put a pin in ``pin_mode``; an output starts at the level last written to it."""
        if self._pins.check_mode(identifier, pin_mode):
            state = self._pins.digital(identifier)
            wanted = DigitalPinState(pin_mode, state.level)
            # A mode change waits for the board's acknowledgement (even where commands
            # are confirmed later): the mode remembered is what the pin's calls check.
            with acknowledge_later(False):
                await self._apply_pin(identifier, wanted, mode_changed=True)

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        """Return the mode last set on a pin (the board cannot report it)."""
        return self._pins.mode(identifier)

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        """Drive an output pin high or low."""
        pin = self._pins.output(identifier, "write to it")
        wanted = DigitalPinState(pin.mode, state)
        await self._apply_pin(identifier, wanted, mode_changed=False)

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Return the level last written to an output pin."""
        return self._pins.output(identifier, "read back its last written level").level

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Read the level of an input pin."""
        self._pins.check_input(identifier)
        return await self._read_digital(identifier)

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        """Read the voltage on an analogue pin, in volts."""
        self._pins.check_analogue(identifier, self.ANALOGUE_CHANNELS)
        return await self._read_analogue(identifier)
