"""The conformance suite of :class:`~j5aio.components.gpio_pin.GPIOPinInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable, Collection, Mapping
from dataclasses import dataclass, field
from typing import ClassVar

import pytest

from j5aio.components.gpio_pin import GPIOPin, GPIOPinInterface, GPIOPinMode
from j5aio.numbered import Pins

from ._base import InterfaceConformance, Subject, require

__all__ = ["GPIOPinInterfaceConformance", "GPIOPinSubject", "pin_modes"]

DIGITAL_INPUTS = frozenset({
    GPIOPinMode.DIGITAL_INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP,
    GPIOPinMode.DIGITAL_INPUT_PULLDOWN,
})


@dataclass(kw_only=True)
class GPIOPinSubject(Subject):
    """A backend implementing :class:`.GPIOPinInterface`, for :class:`GPIOPinInterfaceConformance`.

    :param modes: the hardware modes each pin supports, by identifier; a pin not listed
        supports only ``DIGITAL_OUTPUT``.
    :param observe_output: returns the level output pin ``identifier`` really drives
        (read from a simulator, say).
    :param set_input: makes input pin ``identifier`` see level ``high``, so that the next
        digital read sees it. For a console backend: queue the answer to the prompt.
    :param set_voltage: puts ``volts`` on analogue pin ``identifier``, so that the next
        analogue read sees it.
    """

    backend: GPIOPinInterface
    modes: Mapping[int, Collection[GPIOPinMode]] = field(default_factory=dict)
    observe_output: Callable[[int], Awaitable[bool]] | None = None
    set_input: Callable[[int, bool], Awaitable[None]] | None = None
    set_voltage: Callable[[int, float], Awaitable[None]] | None = None

    def modes_of(self, identifier: int) -> Collection[GPIOPinMode]:
        """The hardware modes pin ``identifier`` supports."""
        return self.modes.get(identifier, (GPIOPinMode.DIGITAL_OUTPUT,))

    def pins_with(self, *modes: GPIOPinMode) -> list[tuple[int, GPIOPinMode]]:
        """Each pin supporting one of ``modes``, with the first of them it supports."""
        found = []
        for identifier in self.identifiers:
            supported = [mode for mode in modes if mode in self.modes_of(identifier)]
            if supported:
                found.append((identifier, supported[0]))
        return found


def pin_modes(
    pins: Pins[GPIOPin] | Mapping[int, GPIOPin],
) -> dict[int, frozenset[GPIOPinMode]]:
    """The hardware modes of each pin of a board, as its board definition claims them.

    Pass ``pin_modes(board.pins)`` as the ``modes`` of a :class:`GPIOPinSubject`, so that
    the suite checks the backend can do what the board tells students it can.
    """
    return {identifier: pin.hardware_modes for identifier, pin in pins.items()}


def _some(pins: list[tuple[int, GPIOPinMode]], what: str) -> list[tuple[int, GPIOPinMode]]:
    if not pins:
        pytest.skip(f"no pin of this board supports {what}")
    return pins


class GPIOPinInterfaceConformance(InterfaceConformance[GPIOPinSubject]):
    """What every implementation of :class:`~j5aio.components.gpio_pin.GPIOPinInterface` must do.

    * every mode a pin supports can be set and is read back;
    * the level last written to an output is remembered (and driven), pin by pin;
    * digital reads give a bool that follows the input, analogue reads a float in volts;
    * PWM and DAC writes across [0, 1] are accepted by the pins that have them;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far an analogue reading may be from the voltage applied, in volts.
    voltage_tolerance: ClassVar[float] = 0.05

    #: The voltages the analogue test applies, in volts.
    voltages: ClassVar[tuple[float, ...]] = (0.0, 1.25, 3.3, 5.0)

    async def test_set_then_get_mode_round_trips(self, subject: GPIOPinSubject) -> None:
        """Every mode each pin supports is read back once set."""
        with self.bounded():
            for identifier in subject.identifiers:
                for mode in sorted(subject.modes_of(identifier)):
                    await subject.backend.set_gpio_pin_mode(identifier, mode)
                    got = await subject.backend.get_gpio_pin_mode(identifier)
                    assert got == mode, f"pin {identifier} was set to {mode!r}, reads {got!r}"

    async def _check_output(self, subject: GPIOPinSubject, identifier: int, high: bool) -> None:
        await self.assert_read_back(
            f"pin {identifier} was written {high}", identifier,
            subject.backend.get_gpio_pin_digital_state, subject.observe_output,
            lambda value: value is high,
        )

    async def test_digital_write_is_remembered(self, subject: GPIOPinSubject) -> None:
        """The level last written to an output pin is the level reported (and driven)."""
        pins = _some(subject.pins_with(GPIOPinMode.DIGITAL_OUTPUT), "digital output")
        identifier = pins[0][0]
        with self.bounded():
            await subject.backend.set_gpio_pin_mode(identifier, GPIOPinMode.DIGITAL_OUTPUT)
            for high in (True, True, False, False, True, False):
                await subject.backend.write_gpio_pin_digital_state(identifier, high)
                await self._check_output(subject, identifier, high)

    async def test_every_identifier(self, subject: GPIOPinSubject) -> None:
        """Every output pin can be driven high alone; the others stay low."""
        pins = [i for i, _ in _some(
            subject.pins_with(GPIOPinMode.DIGITAL_OUTPUT), "digital output",
        )]
        with self.bounded():
            for identifier in pins:
                await subject.backend.set_gpio_pin_mode(identifier, GPIOPinMode.DIGITAL_OUTPUT)
                await subject.backend.write_gpio_pin_digital_state(identifier, False)
            for identifier in pins:
                await subject.backend.write_gpio_pin_digital_state(identifier, True)
                for other in pins:
                    await self._check_output(subject, other, other == identifier)
                await subject.backend.write_gpio_pin_digital_state(identifier, False)

    async def test_digital_read_follows_the_input(self, subject: GPIOPinSubject) -> None:
        """A digital read gives a bool: the level on the pin."""
        pins = _some(subject.pins_with(*sorted(DIGITAL_INPUTS)), "digital input")
        with self.bounded():
            for identifier, mode in pins:
                await subject.backend.set_gpio_pin_mode(identifier, mode)
                for high in (True, False, True, False):
                    if subject.set_input is not None:
                        await subject.set_input(identifier, high)
                    got = await subject.backend.read_gpio_pin_digital_state(identifier)
                    assert isinstance(got, bool), f"pin {identifier} read as {got!r}"
                    if subject.set_input is not None:
                        assert got is high, f"pin {identifier} is at {high} but reads {got}"

    async def test_analogue_read_follows_the_voltage(self, subject: GPIOPinSubject) -> None:
        """An analogue read gives the voltage on the pin, in volts."""
        set_voltage = require(subject.set_voltage, "set_voltage")
        pins = _some(subject.pins_with(GPIOPinMode.ANALOGUE_INPUT), "analogue input")
        with self.bounded():
            for identifier, mode in pins:
                await subject.backend.set_gpio_pin_mode(identifier, mode)
                for volts in self.voltages:
                    await set_voltage(identifier, volts)
                    got = await subject.backend.read_gpio_pin_analogue_value(identifier)
                    assert isinstance(got, float), f"pin {identifier} read as {got!r}"
                    assert math.isclose(got, volts, abs_tol=self.voltage_tolerance), (
                        f"pin {identifier} is at {volts} V but reads {got} V"
                    )

    async def test_analogue_read_is_a_float(self, subject: GPIOPinSubject) -> None:
        """An analogue read gives a finite float, even with nothing fed to the pin."""
        pins = _some(subject.pins_with(GPIOPinMode.ANALOGUE_INPUT), "analogue input")
        with self.bounded():
            for identifier, mode in pins:
                await subject.backend.set_gpio_pin_mode(identifier, mode)
                if subject.set_voltage is not None:
                    await subject.set_voltage(identifier, self.voltages[1])
                got = await subject.backend.read_gpio_pin_analogue_value(identifier)
                assert isinstance(got, float), f"pin {identifier} read as {got!r}"
                assert math.isfinite(got), f"pin {identifier} read as {got!r}"

    async def test_pwm_and_dac_writes_are_accepted(self, subject: GPIOPinSubject) -> None:
        """Pins with PWM or a DAC take values across [0, 1]."""
        pwm = subject.pins_with(GPIOPinMode.PWM_OUTPUT)
        dac = subject.pins_with(GPIOPinMode.ANALOGUE_OUTPUT)
        _some(pwm + dac, "PWM or analogue output")
        with self.bounded():
            for identifier, mode in pwm:
                await subject.backend.set_gpio_pin_mode(identifier, mode)
                for duty in (0.0, 0.5, 1.0):
                    await subject.backend.write_gpio_pin_pwm_value(identifier, duty)
            for identifier, mode in dac:
                await subject.backend.set_gpio_pin_mode(identifier, mode)
                for value in (0.0, 0.5, 1.0):
                    await subject.backend.write_gpio_pin_dac_value(identifier, value)

    async def test_out_of_range_identifier_raises(self, subject: GPIOPinSubject) -> None:
        """A pin the board does not have is refused, by every call."""
        backend = subject.backend
        await self.assert_refused(
            subject,
            lambda i: backend.set_gpio_pin_mode(i, GPIOPinMode.DIGITAL_OUTPUT),
            "set_gpio_pin_mode",
        )
        await self.assert_refused(subject, backend.get_gpio_pin_mode)
        await self.assert_refused(
            subject,
            lambda i: backend.write_gpio_pin_digital_state(i, True),
            "write_gpio_pin_digital_state",
        )
        await self.assert_refused(subject, backend.get_gpio_pin_digital_state)
        await self.assert_refused(subject, backend.read_gpio_pin_digital_state)
        await self.assert_refused(subject, backend.read_gpio_pin_analogue_value)
