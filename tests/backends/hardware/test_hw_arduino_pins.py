"""The Uno pin rules with and without A0 to A5 as digital pins."""

from __future__ import annotations

import pytest

from j5aio.backends.hardware.arduino_pins import ArduinoPins
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError


def test_analogue_pins_stay_analogue_unless_the_firmware_drives_them() -> None:
    pins = ArduinoPins("SB Arduino")
    assert pins.mode(14) is GPIOPinMode.ANALOGUE_INPUT
    with pytest.raises(NotSupportedByHardwareError, match=r"it supports ANALOGUE_INPUT$"):
        pins.check_mode(14, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(NotSupportedByHardwareError, match="is an analogue input"):
        pins.digital(15)
    assert pins.check_mode(14, GPIOPinMode.ANALOGUE_INPUT) is False


def test_analogue_pins_as_digital_pins() -> None:
    pins = ArduinoPins("Ruggeduino", analogue_pins_digital=True)
    assert pins.mode(14) is GPIOPinMode.ANALOGUE_INPUT
    assert pins.check_mode(14, GPIOPinMode.ANALOGUE_INPUT) is False  # nothing to tell
    assert pins.check_mode(14, GPIOPinMode.DIGITAL_OUTPUT) is True
    pins.digital(14).mode = GPIOPinMode.DIGITAL_OUTPUT
    assert pins.mode(14) is GPIOPinMode.DIGITAL_OUTPUT
    assert pins.check_mode(14, GPIOPinMode.ANALOGUE_INPUT) is True  # it must stop driving
    with pytest.raises(
        NotSupportedByHardwareError,
        match="supports ANALOGUE_INPUT, DIGITAL_INPUT, DIGITAL_INPUT_PULLUP, DIGITAL_OUTPUT",
    ):
        pins.check_mode(19, GPIOPinMode.PWM_OUTPUT)
    with pytest.raises(NotSupportedByHardwareError):
        pins.check_mode(3, GPIOPinMode.ANALOGUE_INPUT)
