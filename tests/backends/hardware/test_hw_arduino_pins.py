"""The Uno pin rules with and without A0 to A5 as digital pins."""

from __future__ import annotations

import pytest

from j5aio.backends.hardware.arduino_pins import ArduinoPins, DigitalPinState, wire_mode
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError
from tests.dataclass_twins import assert_like_generated


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


def test_every_pin_digital_with_analogue_readings_only_in_analogue_input_mode() -> None:
    # The SR Arduino fw 2 and SB sb2024 rules: every pin starts as a digital input.
    pins = ArduinoPins("SR Arduino", analogue_mode_required=True)
    assert pins.analogue_pins_digital
    assert pins.mode(14) is GPIOPinMode.DIGITAL_INPUT
    with pytest.raises(ValueError, match="must be in ANALOGUE_INPUT mode to read a voltage"):
        pins.check_analogue(14)
    assert pins.check_mode(14, GPIOPinMode.ANALOGUE_INPUT) is True
    pins.record(14, mode=GPIOPinMode.ANALOGUE_INPUT)
    pins.check_analogue(14)
    with pytest.raises(NotSupportedByHardwareError, match=r"pins 14 to 19 \(A0 to A5\) only"):
        pins.check_analogue(3)
    assert wire_mode(GPIOPinMode.ANALOGUE_INPUT) is GPIOPinMode.DIGITAL_INPUT
    assert wire_mode(GPIOPinMode.DIGITAL_OUTPUT) is GPIOPinMode.DIGITAL_OUTPUT


def test_the_state_is_a_copy_and_record_changes_the_table() -> None:
    pins = ArduinoPins("Ruggeduino", analogue_pins_digital=True)
    pins.state(3).level = True
    assert pins.state(3).level is False
    pins.record(3, mode=GPIOPinMode.DIGITAL_OUTPUT, level=True)
    assert pins.output(3, "write to it").level is True
    with pytest.raises(ValueError, match="must be in DIGITAL_OUTPUT mode to read it back"):
        pins.output(4, "read it back")


@pytest.mark.parametrize(
    ("rules", "analogue_start"),
    [
        ({}, GPIOPinMode.ANALOGUE_INPUT),
        ({"analogue_pins_digital": True}, GPIOPinMode.ANALOGUE_INPUT),
        ({"analogue_mode_required": True}, GPIOPinMode.DIGITAL_INPUT),
    ],
)
def test_reset_returns_to_power_on_under_the_same_rules(
    rules: dict[str, bool], analogue_start: GPIOPinMode
) -> None:
    # A board that came back is reset: its rules (A0 to A5 digital or not) stay.
    pins = ArduinoPins("Arduino", **rules)
    digital_analogue = pins.analogue_pins_digital
    pins.record(5, mode=GPIOPinMode.DIGITAL_OUTPUT, level=True)
    if digital_analogue:
        pins.record(15, mode=GPIOPinMode.DIGITAL_OUTPUT)
    pins.reset()
    assert pins.analogue_pins_digital is digital_analogue
    assert pins.state(5) == DigitalPinState()
    assert pins.mode(15) is analogue_start
    with pytest.raises(ValueError, match="has pins 2 to 19, not pin 20"):
        pins.mode(20)
    with pytest.raises(TypeError, match="must be an int, not bool"):
        pins.mode(True)


def test_a_digital_pin_state_is_the_generated_dataclass() -> None:
    assert_like_generated(
        DigitalPinState,
        [((), {}), ((GPIOPinMode.DIGITAL_OUTPUT, True), {}), ((), {"level": True})],
        frozen=False,
    )
    state = DigitalPinState()
    state.level = True
    assert state == DigitalPinState(level=True) != DigitalPinState()
