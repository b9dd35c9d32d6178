"""GPIO pins: a pin that can be a digital input or output, analogue input, and more."""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Set as AbstractSet
from enum import IntEnum
from typing import TYPE_CHECKING, ClassVar, TypeGuard

from j5aio.components._checks import check_bool, check_number, describe
from j5aio.components.component import DerivedComponent, Interface
from j5aio.components.identified import IdentifiedComponent
from j5aio.errors import BadGPIOPinModeError, NotSupportedByComponentError

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend

__all__ = ["FirmwareMode", "GPIOPin", "GPIOPinInterface", "GPIOPinMode", "PinMode"]


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


_DIGITAL_INPUTS = frozenset({
    GPIOPinMode.DIGITAL_INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP,
    GPIOPinMode.DIGITAL_INPUT_PULLDOWN,
})


def _check_fraction(value: object, name: str, meaning: str) -> float:
    """Return ``value`` as a float if it is in [0, 1]; ``meaning`` says what it stands for."""
    return check_number(
        value, name=name, low=0.0, high=1.0, allowed=f"a float between 0 and 1 ({meaning})",
    )


def _is_pin_mode(mode: object) -> TypeGuard[PinMode]:
    """Tell whether ``mode`` is a hardware mode or a firmware mode."""
    if isinstance(mode, GPIOPinMode):
        return True
    return isinstance(mode, type) and issubclass(mode, DerivedComponent)


def _mode_name(mode: PinMode) -> str:
    """Name a pin mode for an error message: ``DIGITAL_OUTPUT``, ``UltrasoundSensor``."""
    return mode.name if isinstance(mode, GPIOPinMode) else mode.__name__


def _mode_names(modes: AbstractSet[PinMode]) -> str:
    """Name several pin modes, hardware modes first, in a stable order."""
    hardware = sorted(mode for mode in modes if isinstance(mode, GPIOPinMode))
    firmware = sorted(
        (mode for mode in modes if not isinstance(mode, GPIOPinMode)),
        key=lambda mode: mode.__name__,
    )
    ordered: list[PinMode] = [*hardware, *firmware]
    return ", ".join(_mode_name(mode) for mode in ordered)


class GPIOPin(IdentifiedComponent[GPIOPinInterface]):
    """A general-purpose input/output pin.

    A pin works in one *mode* at a time: a hardware mode (:class:`GPIOPinMode`, such as
    ``DIGITAL_OUTPUT`` or ``ANALOGUE_INPUT``) or a firmware mode (a derived component,
    such as an ultrasound sensor, that the board's firmware drives on the pin). Put the
    pin in a mode with ``await pin.set_mode(GPIOPinMode.DIGITAL_INPUT)``; each read or
    write checks that the pin is in a mode that allows it.

    :param identifier: the number of the pin on its board.
    :param backend: the backend that drives the pin.
    :param initial_mode: the mode :meth:`setup` puts the pin in.
    :param hardware_modes: the hardware modes the pin supports (at least one).
    :param firmware_modes: the firmware modes the pin supports.
    :raises ValueError: ``hardware_modes`` is empty.
    :raises TypeError: ``initial_mode`` is not a pin mode.
    :raises NotSupportedByComponentError: the pin does not support ``initial_mode``.
    """

    #: The hardware modes of a pin, unless told otherwise.
    DEFAULT_HW_MODE: ClassVar[frozenset[GPIOPinMode]] = frozenset({GPIOPinMode.DIGITAL_OUTPUT})
    #: The firmware modes of a pin, unless told otherwise.
    DEFAULT_FW_MODE: ClassVar[frozenset[FirmwareMode]] = frozenset()

    __slots__ = ("_firmware_modes", "_hardware_modes", "_initial_mode", "_is_set_up")

    def __init__(
        self,
        identifier: int,
        backend: GPIOPinInterface | Backend,
        *,
        initial_mode: PinMode,
        hardware_modes: AbstractSet[GPIOPinMode] = DEFAULT_HW_MODE,
        firmware_modes: AbstractSet[FirmwareMode] = DEFAULT_FW_MODE,
    ) -> None:
        super().__init__(identifier, backend)
        if not hardware_modes:
            raise ValueError(
                f"GPIO pin {identifier} must support at least one hardware mode "
                "(a GPIOPinMode); got none",
            )
        self._hardware_modes = frozenset(hardware_modes)
        self._firmware_modes = frozenset(firmware_modes)
        self._check_mode(initial_mode)
        self._initial_mode = initial_mode
        self._is_set_up = False

    @classmethod
    def interface_class(cls) -> type[GPIOPinInterface]:
        """The interface a backend implements to drive pins: :class:`GPIOPinInterface`."""
        return GPIOPinInterface

    @property
    def hardware_modes(self) -> frozenset[GPIOPinMode]:
        """The hardware modes this pin supports."""
        return self._hardware_modes

    @property
    def firmware_modes(self) -> frozenset[FirmwareMode]:
        """The firmware modes (derived component classes) this pin supports."""
        return self._firmware_modes

    @firmware_modes.setter
    def firmware_modes(self, modes: AbstractSet[FirmwareMode]) -> None:
        """Replace the firmware modes this pin supports (boards do this when set up)."""
        self._firmware_modes = frozenset(modes)

    async def setup(self) -> None:
        """Put the pin in its initial mode.

        The board calls this when it is set up; calling it again does nothing.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        if self._is_set_up:
            return
        await self.set_mode(self._initial_mode)
        self._is_set_up = True

    async def get_mode(self) -> PinMode:
        """Return the pin's hardware mode, as the backend reports it.

        As in j5, a firmware mode set with :meth:`set_mode` is not reported here: the
        board only knows the pin's hardware mode.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_gpio_pin_mode(self._identifier)

    async def set_mode(self, mode: PinMode) -> None:
        """Put the pin in ``mode``.

        A hardware mode is sent to the board. A firmware mode is only checked: the
        derived component that uses it (an ultrasound sensor, say) drives the pin.

        :raises TypeError: ``mode`` is neither a :class:`GPIOPinMode` nor a derived
            component class.
        :raises NotSupportedByComponentError: this pin does not support ``mode``.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        self._check_mode(mode)
        if isinstance(mode, GPIOPinMode):
            await self._backend.set_gpio_pin_mode(self._identifier, mode)

    async def digital_write(self, state: bool) -> None:
        """Drive the pin high (``True``) or low (``False``).

        :raises TypeError: ``state`` is not a bool.
        :raises BadGPIOPinModeError: the pin is not in ``DIGITAL_OUTPUT`` mode.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        check_bool(state, name="a digital pin state", allowed="True (high) or False (low)")
        await self._require_mode("digital_write", {GPIOPinMode.DIGITAL_OUTPUT})
        await self._backend.write_gpio_pin_digital_state(self._identifier, state)

    async def get_last_digital_write(self) -> bool:
        """Return the level last written with :meth:`digital_write`, without reading the pin.

        :raises BadGPIOPinModeError: the pin is not in ``DIGITAL_OUTPUT`` mode.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._require_mode("get_last_digital_write", {GPIOPinMode.DIGITAL_OUTPUT})
        return await self._backend.get_gpio_pin_digital_state(self._identifier)

    async def digital_read(self) -> bool:
        """Read the pin: ``True`` if it is high, ``False`` if it is low.

        :raises BadGPIOPinModeError: the pin is not in one of the digital input modes.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._require_mode("digital_read", _DIGITAL_INPUTS)
        return await self._backend.read_gpio_pin_digital_state(self._identifier)

    async def analogue_read(self) -> float:
        """Read the voltage on the pin, in volts.

        :raises BadGPIOPinModeError: the pin is not in ``ANALOGUE_INPUT`` mode.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._require_mode("analogue_read", {GPIOPinMode.ANALOGUE_INPUT})
        return await self._backend.read_gpio_pin_analogue_value(self._identifier)

    async def analogue_write(self, value: float) -> None:
        """Set the pin's output voltage, as a fraction of the largest it can give.

        :param value: a number between 0 (no voltage) and 1 (the full voltage).
        :raises TypeError: ``value`` is not a number (or is a bool).
        :raises ValueError: ``value`` is outside [0, 1], or NaN.
        :raises BadGPIOPinModeError: the pin is not in ``ANALOGUE_OUTPUT`` mode.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        scaled = _check_fraction(
            value, "an analogue output value", "the fraction of the full voltage",
        )
        await self._require_mode("analogue_write", {GPIOPinMode.ANALOGUE_OUTPUT})
        await self._backend.write_gpio_pin_dac_value(self._identifier, scaled)

    async def pwm_write(self, duty_cycle: float) -> None:
        """Output a PWM signal that is high for ``duty_cycle`` of the time.

        :param duty_cycle: a number between 0 (always low) and 1 (always high).
        :raises TypeError: ``duty_cycle`` is not a number (or is a bool).
        :raises ValueError: ``duty_cycle`` is outside [0, 1], or NaN.
        :raises BadGPIOPinModeError: the pin is not in ``PWM_OUTPUT`` mode.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        duty = _check_fraction(duty_cycle, "a PWM duty cycle", "the fraction of time it is high")
        await self._require_mode("pwm_write", {GPIOPinMode.PWM_OUTPUT})
        await self._backend.write_gpio_pin_pwm_value(self._identifier, duty)

    def _check_mode(self, mode: object) -> None:
        """Check that ``mode`` is a pin mode this pin supports."""
        if _is_pin_mode(mode):
            supported: frozenset[PinMode] = self._hardware_modes | self._firmware_modes
            if mode not in supported:
                raise NotSupportedByComponentError(
                    f"pin {self._identifier} does not support mode "
                    f"{_mode_name(mode)}; it supports: {_mode_names(supported)}",
                )
            return
        raise TypeError(
            "a pin mode must be a GPIOPinMode or a firmware mode (a derived component "
            f"class such as UltrasoundSensor); got {describe(mode)}",
        )

    async def _require_mode(self, operation: str, allowed: AbstractSet[GPIOPinMode]) -> None:
        """Check that the pin is in one of the ``allowed`` modes for ``operation``."""
        mode = await self.get_mode()
        if mode not in allowed:
            raise BadGPIOPinModeError(
                f"pin {self._identifier} is in mode {_mode_name(mode)}, but {operation} "
                f"needs it to be in {_mode_names(allowed)}; change it with set_mode() first",
            )
