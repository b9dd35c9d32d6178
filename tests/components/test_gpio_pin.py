import math
from collections.abc import Awaitable, Callable

import pytest

from j5aio.components import GPIOPin, GPIOPinInterface, GPIOPinMode, UltrasoundSensor
from j5aio.errors import BadGPIOPinModeError, NotSupportedByComponentError

from .component_fakes import RecordingBackend

ALL_HARDWARE = frozenset(GPIOPinMode)
INPUTS = [
    GPIOPinMode.DIGITAL_INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP,
    GPIOPinMode.DIGITAL_INPUT_PULLDOWN,
]


def make_pin(
    backend: RecordingBackend,
    mode: GPIOPinMode,
    *,
    identifier: int = 5,
) -> GPIOPin:
    backend.pin_mode = mode
    return GPIOPin(
        identifier,
        backend,
        initial_mode=mode,
        hardware_modes=ALL_HARDWARE,
        firmware_modes={UltrasoundSensor},
    )


async def test_setup_applies_the_initial_mode_once() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(
        2,
        backend,
        initial_mode=GPIOPinMode.ANALOGUE_INPUT,
        hardware_modes={GPIOPinMode.ANALOGUE_INPUT, GPIOPinMode.DIGITAL_INPUT},
    )
    assert backend.calls == []  # nothing is sent before setup

    await pin.setup()
    await pin.setup()
    assert backend.calls == [("set_gpio_pin_mode", (2, GPIOPinMode.ANALOGUE_INPUT))]


async def test_setup_with_a_firmware_initial_mode_sends_nothing() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(
        2, backend, initial_mode=UltrasoundSensor, firmware_modes={UltrasoundSensor},
    )
    await pin.setup()
    assert backend.calls == []


async def test_default_modes_are_digital_output_only() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(0, backend, initial_mode=GPIOPinMode.DIGITAL_OUTPUT)
    assert pin.hardware_modes == {GPIOPinMode.DIGITAL_OUTPUT}
    assert pin.firmware_modes == frozenset()
    with pytest.raises(NotSupportedByComponentError):
        await pin.set_mode(GPIOPinMode.DIGITAL_INPUT)


def test_a_pin_needs_a_hardware_mode() -> None:
    with pytest.raises(ValueError, match=r"GPIO pin 3 must support at least one hardware mode"):
        GPIOPin(
            3, RecordingBackend(), initial_mode=GPIOPinMode.DIGITAL_OUTPUT, hardware_modes=set(),
        )


def test_an_unsupported_initial_mode_is_refused_when_the_pin_is_made() -> None:
    with pytest.raises(
        NotSupportedByComponentError,
        match=r"^pin 3 does not support mode ANALOGUE_INPUT; it supports: DIGITAL_OUTPUT$",
    ):
        GPIOPin(3, RecordingBackend(), initial_mode=GPIOPinMode.ANALOGUE_INPUT)


async def test_set_mode_sends_a_hardware_mode_and_get_mode_reads_it() -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.DIGITAL_OUTPUT)

    await pin.set_mode(GPIOPinMode.PWM_OUTPUT)
    assert await pin.get_mode() is GPIOPinMode.PWM_OUTPUT
    assert backend.calls == [
        ("set_gpio_pin_mode", (5, GPIOPinMode.PWM_OUTPUT)),
        ("get_gpio_pin_mode", (5,)),
    ]


async def test_set_mode_accepts_a_supported_firmware_mode_without_sending_it() -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.DIGITAL_OUTPUT)
    await pin.set_mode(UltrasoundSensor)
    assert backend.calls == []


async def test_set_mode_refuses_an_unsupported_mode_naming_what_is_supported() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(
        7,
        backend,
        initial_mode=GPIOPinMode.DIGITAL_INPUT,
        hardware_modes={GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_OUTPUT},
        firmware_modes={UltrasoundSensor},
    )
    with pytest.raises(NotSupportedByComponentError) as info:
        await pin.set_mode(GPIOPinMode.PWM_OUTPUT)
    assert str(info.value) == (
        "pin 7 does not support mode PWM_OUTPUT; "
        "it supports: DIGITAL_INPUT, DIGITAL_OUTPUT, UltrasoundSensor"
    )
    assert backend.calls == []


async def test_set_mode_refuses_a_firmware_mode_the_pin_lacks() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(1, backend, initial_mode=GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(NotSupportedByComponentError, match=r"not support mode UltrasoundSensor"):
        await pin.set_mode(UltrasoundSensor)


@pytest.mark.parametrize("mode", [3, "DIGITAL_OUTPUT", None, GPIOPin])
async def test_set_mode_refuses_something_that_is_not_a_mode(mode: object) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(TypeError, match=r"^a pin mode must be a GPIOPinMode or a firmware mode"):
        await pin.set_mode(mode)  # type: ignore[arg-type]
    assert backend.calls == []


async def test_firmware_modes_can_be_replaced() -> None:
    backend = RecordingBackend()
    pin = GPIOPin(1, backend, initial_mode=GPIOPinMode.DIGITAL_OUTPUT)
    pin.firmware_modes = {UltrasoundSensor}
    assert pin.firmware_modes == frozenset({UltrasoundSensor})
    await pin.set_mode(UltrasoundSensor)


async def test_digital_write_and_last_digital_write_in_output_mode() -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.DIGITAL_OUTPUT)

    await pin.digital_write(True)
    assert await pin.get_last_digital_write() is True
    assert backend.calls == [
        ("get_gpio_pin_mode", (5,)),
        ("write_gpio_pin_digital_state", (5, True)),
        ("get_gpio_pin_mode", (5,)),
        ("get_gpio_pin_digital_state", (5,)),
    ]


@pytest.mark.parametrize("mode", INPUTS)
async def test_digital_read_in_every_input_mode(mode: GPIOPinMode) -> None:
    backend = RecordingBackend()
    backend.pin_level = True
    pin = make_pin(backend, mode)

    assert await pin.digital_read() is True
    assert backend.names() == ["get_gpio_pin_mode", "read_gpio_pin_digital_state"]


async def test_analogue_read_in_analogue_input_mode() -> None:
    backend = RecordingBackend()
    backend.analogue = 3.3
    pin = make_pin(backend, GPIOPinMode.ANALOGUE_INPUT)
    assert await pin.analogue_read() == 3.3
    assert backend.names() == ["get_gpio_pin_mode", "read_gpio_pin_analogue_value"]


@pytest.mark.parametrize("value", [0, 0.5, 1])
async def test_analogue_write_in_analogue_output_mode(value: float) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.ANALOGUE_OUTPUT)
    await pin.analogue_write(value)
    assert backend.calls[-1] == ("write_gpio_pin_dac_value", (5, float(value)))


@pytest.mark.parametrize("value", [0, 0.25, 1.0])
async def test_pwm_write_in_pwm_mode(value: float) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.PWM_OUTPUT)
    await pin.pwm_write(value)
    assert backend.calls[-1] == ("write_gpio_pin_pwm_value", (5, float(value)))


Operation = Callable[[GPIOPin], Awaitable[object]]

OPERATIONS: list[tuple[str, Operation, set[GPIOPinMode]]] = [
    ("digital_write", lambda pin: pin.digital_write(True), {GPIOPinMode.DIGITAL_OUTPUT}),
    ("get_last_digital_write", GPIOPin.get_last_digital_write, {GPIOPinMode.DIGITAL_OUTPUT}),
    ("digital_read", GPIOPin.digital_read, set(INPUTS)),
    ("analogue_read", GPIOPin.analogue_read, {GPIOPinMode.ANALOGUE_INPUT}),
    ("analogue_write", lambda pin: pin.analogue_write(0.5), {GPIOPinMode.ANALOGUE_OUTPUT}),
    ("pwm_write", lambda pin: pin.pwm_write(0.5), {GPIOPinMode.PWM_OUTPUT}),
]


@pytest.mark.parametrize(
    ("name", "operation", "mode"),
    [
        (name, operation, mode)
        for name, operation, allowed in OPERATIONS
        for mode in GPIOPinMode
        if mode not in allowed
    ],
)
async def test_each_operation_in_a_wrong_mode_raises_bad_gpio_pin_mode(
    name: str, operation: Operation, mode: GPIOPinMode,
) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, mode, identifier=8)

    with pytest.raises(BadGPIOPinModeError) as info:
        await operation(pin)
    message = str(info.value)
    assert message.startswith(f"pin 8 is in mode {mode.name}, but {name} needs it to be in ")
    assert message.endswith("; change it with set_mode() first")
    assert backend.names() == ["get_gpio_pin_mode"]  # nothing was written or read


async def test_bad_mode_message_lists_every_allowed_mode() -> None:
    pin = make_pin(RecordingBackend(), GPIOPinMode.DIGITAL_OUTPUT, identifier=2)
    with pytest.raises(
        BadGPIOPinModeError,
        match=r"^pin 2 is in mode DIGITAL_OUTPUT, but digital_read needs it to be in "
        r"DIGITAL_INPUT, DIGITAL_INPUT_PULLUP, DIGITAL_INPUT_PULLDOWN;",
    ):
        await pin.digital_read()


@pytest.mark.parametrize("state", [1, 0, "high", None])
async def test_digital_write_refuses_anything_but_a_bool(state: object) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(
        TypeError, match=r"^a digital pin state must be True \(high\) or False \(low\); got",
    ):
        await pin.digital_write(state)  # type: ignore[arg-type]
    assert backend.calls == []


@pytest.mark.parametrize("value", [-0.1, 1.01, 2, math.nan, math.inf])
async def test_analogue_write_refuses_a_value_outside_0_to_1(value: float) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.ANALOGUE_OUTPUT)
    with pytest.raises(
        ValueError, match=r"^an analogue output value must be a float between 0 and 1",
    ):
        await pin.analogue_write(value)
    assert backend.calls == []


@pytest.mark.parametrize("value", [-0.1, 1.01, math.nan])
async def test_pwm_write_refuses_a_value_outside_0_to_1(value: float) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.PWM_OUTPUT)
    with pytest.raises(
        ValueError, match=r"^a PWM duty cycle must be a float between 0 and 1 \(the fraction of",
    ):
        await pin.pwm_write(value)
    assert backend.calls == []


@pytest.mark.parametrize("value", [True, "0.5", None])
async def test_pwm_and_analogue_writes_refuse_a_value_of_the_wrong_type(value: object) -> None:
    backend = RecordingBackend()
    pin = make_pin(backend, GPIOPinMode.PWM_OUTPUT)
    with pytest.raises(TypeError, match=r"got"):
        await pin.pwm_write(value)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"got"):
        await pin.analogue_write(value)  # type: ignore[arg-type]
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    pin = GPIOPin(13, RecordingBackend(), initial_mode=GPIOPinMode.DIGITAL_OUTPUT)
    assert pin.identifier == 13
    assert GPIOPin.interface_class() is GPIOPinInterface
