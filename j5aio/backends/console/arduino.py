"""ArduinoConsoleBackend: the console backend shared by the boards built on an Arduino Uno."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.components.gpio_pin import GPIOPinInterface, GPIOPinMode
from j5aio.components.led import LEDInterface
from j5aio.errors import BadGPIOPinModeError, NotSupportedByHardwareError

__all__ = ["ArduinoConsoleBackend", "PinState"]

_DIGITAL_INPUT_MODES = frozenset(
    {
        GPIOPinMode.DIGITAL_INPUT,
        GPIOPinMode.DIGITAL_INPUT_PULLUP,
        GPIOPinMode.DIGITAL_INPUT_PULLDOWN,
    },
)


@dataclass
class PinState:
    """What the console remembers of one pin: its mode and the level last written."""

    mode: GPIOPinMode = GPIOPinMode.DIGITAL_OUTPUT
    digital_state: bool = False


class ArduinoConsoleBackend(GPIOPinInterface, LEDInterface, ConsoleBackend):
    """The pins and LED of an Arduino Uno on the console.

    Mode changes and writes are printed; digital and analogue reads are asked for. A
    subclass sets ``board`` and adds the interfaces of its board's other components.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    #: The pin numbers: digital pins 2 to 13, then analogue pins A0 to A5 (14 to 19).
    PINS: ClassVar[range] = range(2, 20)

    #: The pins that can read an analogue voltage.
    ANALOGUE_PINS: ClassVar[range] = range(14, 20)

    #: The pin the LED is wired to.
    LED_PIN: ClassVar[int] = 13

    _UNO_MODES: ClassVar[frozenset[GPIOPinMode]] = frozenset(
        {
            GPIOPinMode.DIGITAL_INPUT,
            GPIOPinMode.DIGITAL_INPUT_PULLUP,
            GPIOPinMode.DIGITAL_OUTPUT,
            GPIOPinMode.ANALOGUE_INPUT,
        },
    )

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._pins = {number: PinState() for number in self.PINS}

    def _pin(self, identifier: int) -> PinState:
        self._check_identifier("pin", identifier, self.PINS)
        return self._pins[identifier]

    def _require_mode(
        self, identifier: int, modes: frozenset[GPIOPinMode], action: str,
    ) -> PinState:
        pin = self._pin(identifier)
        if pin.mode not in modes:
            needed = " or ".join(sorted(mode.name for mode in modes))
            raise BadGPIOPinModeError(
                f"pin {identifier} is in mode {pin.mode.name}; it needs to be in mode "
                f"{needed} to {action}",
            )
        return pin

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        """Print the new mode of pin ``identifier``.

        :raises NotSupportedByHardwareError: the Uno's pin cannot work in that mode.
        """
        pin = self._pin(identifier)
        if pin_mode not in self._UNO_MODES or (
            pin_mode is GPIOPinMode.ANALOGUE_INPUT and identifier not in self.ANALOGUE_PINS
        ):
            raise NotSupportedByHardwareError(
                f"pin {identifier} of an Arduino Uno cannot work in mode {pin_mode.name}",
            )
        await self._console.info(f"Set pin {identifier} to {pin_mode.name}")
        pin.mode = pin_mode

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        """Return the mode pin ``identifier`` was last set to."""
        return self._pin(identifier).mode

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        """Print the level written to output pin ``identifier``.

        :raises BadGPIOPinModeError: the pin is not a digital output.
        """
        pin = self._require_mode(
            identifier, frozenset({GPIOPinMode.DIGITAL_OUTPUT}), "set its digital state",
        )
        await self._console.info(f"Set pin {identifier} state to {state}")
        pin.digital_state = state

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Return the level last written to output pin ``identifier``.

        :raises BadGPIOPinModeError: the pin is not a digital output.
        """
        pin = self._require_mode(
            identifier, frozenset({GPIOPinMode.DIGITAL_OUTPUT}), "get its digital state",
        )
        return pin.digital_state

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Ask for the level of input pin ``identifier``.

        :raises BadGPIOPinModeError: the pin is not a digital input.
        """
        self._require_mode(identifier, _DIGITAL_INPUT_MODES, "read its digital state")
        return await self._console.read(f"Pin {identifier} digital state [true/false]", bool)

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        """Ask for the voltage on analogue pin ``identifier``.

        :raises BadGPIOPinModeError: the pin is not an analogue input.
        """
        self._require_mode(
            identifier, frozenset({GPIOPinMode.ANALOGUE_INPUT}), "read its analogue value",
        )
        return await self._console.read(f"Pin {identifier} ADC state [float]", float)

    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        """Refuse: an Arduino Uno has no DAC.

        :raises NotSupportedByHardwareError: always.
        """
        raise NotSupportedByHardwareError(
            f"pin {identifier} cannot output an analogue voltage: an Arduino Uno has no DAC",
        )

    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        """Refuse: the firmware of these boards has no PWM output.

        :raises NotSupportedByHardwareError: always.
        """
        raise NotSupportedByHardwareError(
            f"pin {identifier} cannot output PWM: the board's firmware does not support it",
        )

    def _check_led(self, identifier: int) -> None:
        if identifier != 0:
            raise ValueError(
                f"invalid LED identifier {identifier!r}; an Arduino Uno has only LED 0 "
                f"(digital pin {self.LED_PIN})",
            )

    async def get_led_state(self, identifier: int) -> bool:
        """Return the level last written to the LED's pin (13).

        :raises BadGPIOPinModeError: pin 13 is not a digital output.
        """
        self._check_led(identifier)
        return await self.get_gpio_pin_digital_state(self.LED_PIN)

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or darken the LED by writing its pin (13).

        :raises BadGPIOPinModeError: pin 13 is not a digital output.
        """
        self._check_led(identifier)
        await self.write_gpio_pin_digital_state(self.LED_PIN, state)
