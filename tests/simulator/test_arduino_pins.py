from __future__ import annotations

import pytest

from j5aio.simulator.arduino_pins import ADC_MAX, ANALOGUE_PINS, PIN_COUNT, ArduinoUnoPins, PinMode


def test_power_on_state_is_input_low_without_pull_up() -> None:
    pins = ArduinoUnoPins()
    assert PIN_COUNT == 20
    assert list(ANALOGUE_PINS) == [14, 15, 16, 17, 18, 19]
    for pin in range(PIN_COUNT):
        assert pins.mode(pin) is PinMode.INPUT
        assert pins.output_level(pin) is False
        assert pins.level(pin) is False
        assert pins.input_level(pin) is None


def test_output_drives_its_latch() -> None:
    pins = ArduinoUnoPins()
    pins.pin_mode(5, PinMode.OUTPUT)
    pins.digital_write(5, True)
    assert pins.mode(5) is PinMode.OUTPUT
    assert pins.digital_read(5) is True
    pins.set_input_level(5, False)  # an output is not overridden from outside
    assert pins.digital_read(5) is True


def test_write_on_an_input_switches_the_pull_up() -> None:
    pins = ArduinoUnoPins()
    pins.digital_write(4, True)
    assert pins.mode(4) is PinMode.INPUT_PULLUP
    assert pins.digital_read(4) is True
    pins.digital_write(4, False)
    assert pins.mode(4) is PinMode.INPUT
    assert pins.digital_read(4) is False


def test_pin_modes_and_the_latch() -> None:
    pins = ArduinoUnoPins()
    pins.pin_mode(3, PinMode.INPUT_PULLUP)
    assert pins.output_level(3) is True
    pins.pin_mode(3, PinMode.OUTPUT)  # keeps the latch: now drives high
    assert pins.level(3) is True
    pins.pin_mode(3, PinMode.INPUT)  # clears the latch
    assert pins.output_level(3) is False
    assert pins.mode(3) is PinMode.INPUT


def test_outside_level_beats_the_pull_up() -> None:
    pins = ArduinoUnoPins()
    pins.pin_mode(6, PinMode.INPUT_PULLUP)
    pins.set_input_level(6, False)
    assert pins.digital_read(6) is False
    pins.set_input_level(6, None)
    assert pins.digital_read(6) is True


def test_unknown_pins_are_ignored_by_the_core_functions() -> None:
    pins = ArduinoUnoPins()
    pins.pin_mode(20, PinMode.OUTPUT)
    pins.digital_write(200, True)
    assert pins.digital_read(20) is False
    assert pins.digital_read(-1) is False


def test_reset_keeps_the_outside_world() -> None:
    pins = ArduinoUnoPins()
    pins.pin_mode(2, PinMode.OUTPUT)
    pins.digital_write(2, True)
    pins.set_input_level(3, True)
    pins.set_analogue(14, raw=100)
    pins.reset()
    assert pins.mode(2) is PinMode.INPUT
    assert pins.input_level(3) is True
    assert pins.analogue(14) == 100


def test_analogue_read_takes_channels_and_pin_numbers() -> None:
    pins = ArduinoUnoPins()
    for offset, pin in enumerate(ANALOGUE_PINS):
        pins.set_analogue(pin, raw=100 + offset)
    assert [pins.analog_read(channel) for channel in range(6)] == [100, 101, 102, 103, 104, 105]
    assert [pins.analog_read(pin) for pin in ANALOGUE_PINS] == [100, 101, 102, 103, 104, 105]
    assert pins.analog_read(6) == 0  # ADC6/ADC7 are not bonded out on the Uno
    assert pins.analog_read(20) == 0  # pin 20 -> channel 6
    assert pins.analog_read(224) == 102  # 224 - 14 = 210, & 7 = channel 2
    assert pins.analog_read(-32) == 102  # -32 is 224 as the uint8_t the core receives


def test_analogue_volts_convert_like_the_adc() -> None:
    pins = ArduinoUnoPins()
    pins.set_analogue(15, volts=2.5)
    assert pins.analogue(15) == 512
    pins.set_analogue(15, volts=5.0)
    assert pins.analogue(15) == ADC_MAX
    pins.set_analogue(15, volts=7.0)
    assert pins.analogue(15) == ADC_MAX
    pins.set_analogue(15, volts=-1.0)
    assert pins.analogue(15) == 0
    pins.set_analogue(15, volts=1.0)
    assert pins.analogue(15) == 204


def test_analogue_setting_is_checked() -> None:
    pins = ArduinoUnoPins()
    with pytest.raises(IndexError):
        pins.set_analogue(13, raw=1)
    with pytest.raises(IndexError):
        pins.analogue(20)
    with pytest.raises(ValueError, match="0-1023"):
        pins.set_analogue(14, raw=1024)
    with pytest.raises(TypeError):
        pins.set_analogue(14)
    with pytest.raises(TypeError):
        pins.set_analogue(14, volts=1.0, raw=1)


@pytest.mark.parametrize("pin", [-1, 20])
def test_inspection_checks_the_pin(pin: int) -> None:
    pins = ArduinoUnoPins()
    with pytest.raises(IndexError):
        pins.mode(pin)
    with pytest.raises(IndexError):
        pins.set_input_level(pin, True)
    with pytest.raises(IndexError):
        pins.check_pin(pin)
