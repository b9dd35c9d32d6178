"""GPIO pins: a pin that can be a digital input or output, analogue input, and more."""

from __future__ import annotations

from abc import abstractmethod
from enum import IntEnum

from j5aio.components.component import DerivedComponent, Interface

__all__ = ["FirmwareMode", "GPIOPinInterface", "GPIOPinMode", "PinMode"]


class GPIOPinMode(IntEnum):
    """The hardware modes a GPIO pin can be put in (j5's values)."""

    DIGITAL_INPUT = 0  #: the pin's digital level can be read
    DIGITAL_INPUT_PULLUP = 1  #: as DIGITAL_INPUT, with the internal pull-up enabled
    DIGITAL_INPUT_PULLDOWN = 2  #: as DIGITAL_INPUT, with the internal pull-down enabled
    DIGITAL_OUTPUT = 3  #: the pin's digital level can be set
    ANALOGUE_INPUT = 4  #: the pin's voltage can be read
    ANALOGUE_OUTPUT = 5  #: the pin's voltage can be set through a DAC
    PWM_OUTPUT = 6  #: the pin produces a PWM signal


FirmwareMode = type[DerivedComponent]
"""A firmware mode: a derived component class the board's firmware drives on this pin."""

PinMode = GPIOPinMode | FirmwareMode
"""Any mode a pin can be in: a hardware mode or a firmware mode."""


class GPIOPinInterface(Interface):
    """The coroutines a backend implements to drive GPIO pins."""

    @abstractmethod
    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        """Put pin ``identifier`` in hardware mode ``pin_mode``."""
        raise NotImplementedError

    @abstractmethod
    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        """Return the hardware mode of pin ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        """Drive output pin ``identifier`` high (``True``) or low (``False``)."""
        raise NotImplementedError

    @abstractmethod
    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Return the level last written to output pin ``identifier`` (no read happens)."""
        raise NotImplementedError

    @abstractmethod
    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        """Read the digital level of input pin ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        """Read the voltage on analogue pin ``identifier``, in volts."""
        raise NotImplementedError

    @abstractmethod
    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        """Set the DAC output of pin ``identifier`` to ``scaled_value`` in [0, 1]."""
        raise NotImplementedError

    @abstractmethod
    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        """Set the PWM duty cycle of pin ``identifier`` to ``duty_cycle`` in [0, 1]."""
        raise NotImplementedError
