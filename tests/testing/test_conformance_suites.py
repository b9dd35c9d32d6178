"""The conformance suites themselves: they pass a correct backend and catch broken ones.

No backend of the project has RGB LEDs, so a small reference backend stands in for one.
Every other suite runs against the project's backends in the test_conformance_* modules;
here each is shown failing for a backend broken in a way the suite promises to catch.
"""

from __future__ import annotations

from datetime import timedelta
from typing import Any

import anyio
import pytest

from j5aio.backends.backend import Backend
from j5aio.components.battery_sensor import BatterySensorInterface
from j5aio.components.button import ButtonInterface
from j5aio.components.derived.ultrasound import UltrasoundInterface
from j5aio.components.gpio_pin import GPIOPinInterface, GPIOPinMode
from j5aio.components.led import LEDInterface
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState
from j5aio.components.piezo import PiezoInterface
from j5aio.components.power_output import PowerOutputInterface
from j5aio.components.rgb_led import RGBChannel, RGBLEDInterface
from j5aio.components.servo import ServoInterface, ServoPosition
from j5aio.components.string_command import StringCommandComponentInterface
from j5aio.errors import NotSupportedByHardwareError
from j5aio.testing.conformance import (
    BatterySensorInterfaceConformance,
    BatterySensorSubject,
    ButtonInterfaceConformance,
    ButtonSubject,
    GPIOPinInterfaceConformance,
    GPIOPinSubject,
    LEDInterfaceConformance,
    LEDSubject,
    MotorInterfaceConformance,
    MotorSubject,
    PiezoInterfaceConformance,
    PiezoSubject,
    PowerOutputInterfaceConformance,
    PowerOutputSubject,
    RGBLEDInterfaceConformance,
    RGBLEDSubject,
    ServoInterfaceConformance,
    ServoSubject,
    StringCommandInterfaceConformance,
    StringCommandSubject,
    Subject,
    UltrasoundInterfaceConformance,
    UltrasoundSubject,
)
from j5aio.testing.conformance.motor import same_state
from j5aio.testing.conformance.servo import same_position

Failed = pytest.fail.Exception
Skipped = pytest.skip.Exception


def check(identifier: int, count: int) -> None:
    if identifier not in range(count):
        raise ValueError(f"no identifier {identifier}; there are 0 to {count - 1}")


async def run(suite: Any, test: str, subject: Subject) -> None:
    """Run one test of ``suite`` against ``subject``, as pytest would."""

    class Suite(suite):  # type: ignore[misc]
        async def make_backend(self) -> Subject:
            return subject

    instance = Suite()
    made = await instance.make_backend()
    await getattr(instance, test)(made)


# --- a correct RGB LED backend, run through the whole suite ----------------------------


class ReferenceRGB(RGBLEDInterface):
    """Two RGB LEDs, with 8-bit duty cycles as many boards have."""

    def __init__(self) -> None:
        self.levels = {(i, c): 0 for i in range(2) for c in RGBChannel}
        self.sent = bytearray()

    async def get_rgb_led_channel_duty_cycle(self, identifier: int, channel: RGBChannel) -> float:
        check(identifier, 2)
        return self.levels[identifier, channel] / 255

    async def set_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel, duty_cycle: float,
    ) -> None:
        check(identifier, 2)
        self.levels[identifier, channel] = round(duty_cycle * 255)
        self.sent += b"x"


class TestReferenceRGBLED(RGBLEDInterfaceConformance):
    async def make_backend(self) -> RGBLEDSubject:
        backend = ReferenceRGB()

        async def observe(identifier: int, channel: RGBChannel) -> float:
            return backend.levels[identifier, channel] / 255

        return RGBLEDSubject(
            backend=backend, identifiers=[0, 1], observe=observe,
            traffic=lambda: bytes(backend.sent),
        )


class SharedChannelRGB(ReferenceRGB):
    async def get_rgb_led_channel_duty_cycle(self, identifier: int, channel: RGBChannel) -> float:
        check(identifier, 2)
        return self.levels[identifier, RGBChannel.RED] / 255

    async def set_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel, duty_cycle: float,
    ) -> None:
        await super().set_rgb_led_channel_duty_cycle(identifier, RGBChannel.RED, duty_cycle)


async def test_rgb_suite_catches_shared_channels() -> None:
    subject = RGBLEDSubject(backend=SharedChannelRGB(), identifiers=[0, 1])
    with pytest.raises(AssertionError, match=r"GREEN of RGB LED 0 was set to 0.0 but reads 1.0"):
        await run(RGBLEDInterfaceConformance, "test_every_identifier", subject)


async def test_rgb_suite_catches_a_board_that_shows_something_else() -> None:
    async def observe(identifier: int, channel: RGBChannel) -> float:
        return 0.0

    subject = RGBLEDSubject(backend=ReferenceRGB(), identifiers=[0], observe=observe)
    with pytest.raises(AssertionError, match=r"set to 1.0, the board shows 0.0"):
        await run(RGBLEDInterfaceConformance, "test_set_then_get_round_trips", subject)


# --- bad identifiers, traffic, cleanup: the shared base ----------------------------------


class LeakyLEDs(LEDInterface):
    """Accepts any identifier, and sends bytes before checking."""

    def __init__(self, *, refuse: bool) -> None:
        self.states: dict[int, bool] = {}
        self.sent = bytearray()
        self.refuse = refuse

    async def get_led_state(self, identifier: int) -> bool:
        return self.states.get(identifier, False)

    async def set_led_state(self, identifier: int, state: bool) -> None:
        self.sent += b"L"
        if self.refuse:
            check(identifier, 2)
        self.states[identifier] = state


async def test_bad_identifier_accepted_is_caught() -> None:
    subject = LEDSubject(backend=LeakyLEDs(refuse=False), identifiers=[0, 1])
    with pytest.raises(Failed, match=r"get_led_state accepted bad identifier 2; expected "
                                     "ValueError or LookupError"):
        await run(LEDInterfaceConformance, "test_out_of_range_identifier_raises", subject)


async def test_bytes_sent_for_a_refused_call_are_caught() -> None:
    class Refusing(LeakyLEDs):
        async def get_led_state(self, identifier: int) -> bool:
            check(identifier, 2)
            return await super().get_led_state(identifier)

    backend = Refusing(refuse=True)
    subject = LEDSubject(backend=backend, identifiers=[0, 1], traffic=lambda: bytes(backend.sent))
    with pytest.raises(AssertionError, match=r"set_led_state with bad identifier 2 sent bytes"):
        await run(LEDInterfaceConformance, "test_out_of_range_identifier_raises", subject)


def test_default_bad_identifiers() -> None:
    assert Subject(backend=None, identifiers=[0, 1, 2]).bad_identifiers() == [3, -1]
    assert Subject(backend=None, identifiers=[5], invalid_identifiers=[9]).bad_identifiers() == [9]
    assert Subject(backend=None).sent_so_far() is None
    assert Subject(backend=None, traffic=lambda: b"ab").sent_so_far() == b"ab"


async def test_subject_closes_a_backend_or_runs_its_cleanup() -> None:
    closed: list[str] = []

    class Closing(Backend):
        board = None  # type: ignore[assignment]

        @classmethod
        async def discover(cls) -> list[Any]:
            return []

        @property
        def firmware_version(self) -> None:
            return None

        async def close(self) -> None:
            closed.append("backend")

    async def cleanup() -> None:
        closed.append("cleanup")

    await Subject(backend=Closing()).aclose()
    await Subject(backend=Closing(), cleanup=cleanup).aclose()
    await Subject(backend=object()).aclose()
    assert closed == ["backend", "cleanup"]


class ReferenceLEDs(LEDInterface):
    def __init__(self) -> None:
        self.states = [False, False]

    async def get_led_state(self, identifier: int) -> bool:
        check(identifier, 2)
        return self.states[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        check(identifier, 2)
        self.states[identifier] = state


async def test_led_suite_catches_a_wrong_read_back() -> None:
    class Stuck(ReferenceLEDs):
        async def get_led_state(self, identifier: int) -> bool:
            return False

    subject = LEDSubject(backend=Stuck(), identifiers=[0, 1])
    with pytest.raises(AssertionError, match=r"LED 0 was set to True but reads back False"):
        await run(LEDInterfaceConformance, "test_set_then_get_round_trips", subject)


# --- buttons ------------------------------------------------------------------------------


class EagerButton(ButtonInterface):
    async def get_button_state(self, identifier: int) -> bool:
        check(identifier, 1)
        return 1  # type: ignore[return-value]

    async def wait_until_button_pressed(self, identifier: int) -> None:
        check(identifier, 1)


async def nothing(*_: object) -> None:
    """A hook that does nothing."""


async def test_button_suite_catches_an_early_wait() -> None:
    subject = ButtonSubject(backend=EagerButton(), identifiers=[0], press=nothing)
    with pytest.raises(AssertionError, match=r"returned before any press"):
        await run(ButtonInterfaceConformance, "test_wait_returns_after_a_press", subject)
    with pytest.raises(AssertionError, match=r"returned although nobody pressed"):
        await run(ButtonInterfaceConformance, "test_wait_is_cancellable", subject)


async def test_button_suite_catches_a_non_bool_state() -> None:
    subject = ButtonSubject(backend=EagerButton(), identifiers=[0])
    with pytest.raises(AssertionError, match=r"button 0 read as 1"):
        await run(ButtonInterfaceConformance, "test_state_is_a_bool", subject)
    subject = ButtonSubject(backend=EagerButton(), identifiers=[0], set_pressed=nothing)
    with pytest.raises(AssertionError, match=r"button 0 is held but reads 1"):
        await run(ButtonInterfaceConformance, "test_state_follows_the_button", subject)


async def test_button_suite_skips_without_hooks() -> None:
    subject = ButtonSubject(backend=EagerButton(), identifiers=[0])
    with pytest.raises(Skipped, match=r"needs the 'press' \(or 'set_pressed'\) hook"):
        await run(ButtonInterfaceConformance, "test_wait_returns_after_a_press", subject)
    with pytest.raises(Skipped, match=r"needs the 'set_pressed' hook"):
        await run(ButtonInterfaceConformance, "test_state_follows_the_button", subject)


class PollingButton(ButtonInterface):
    """A wait that polls a held-down flag, as hardware backends do."""

    def __init__(self) -> None:
        self.held = False

    async def get_button_state(self, identifier: int) -> bool:
        check(identifier, 1)
        return self.held

    async def wait_until_button_pressed(self, identifier: int) -> None:
        check(identifier, 1)
        while not self.held:  # noqa: ASYNC110 - polling is the point of this fake
            await anyio.sleep(0.05)


async def test_button_suite_latches_a_press_for_a_polling_backend() -> None:
    backend = PollingButton()
    released: list[int] = []

    async def press(identifier: int) -> None:
        backend.held = True  # latched: no sleep for the poll interval

    async def release(identifier: int) -> None:
        backend.held = False
        released.append(identifier)

    subject = ButtonSubject(backend=backend, identifiers=[0], press=press, release=release)
    await run(ButtonInterfaceConformance, "test_wait_returns_after_a_press", subject)
    assert released == [0]
    assert backend.held is False

    async def set_pressed(identifier: int, pressed: bool) -> None:
        backend.held = pressed

    subject = ButtonSubject(backend=backend, identifiers=[0], set_pressed=set_pressed)
    await run(ButtonInterfaceConformance, "test_wait_works_after_a_cancelled_wait", subject)
    assert backend.held is False


async def test_button_suite_catches_a_wait_that_misses_presses() -> None:
    class Deaf(ButtonInterface):
        async def get_button_state(self, identifier: int) -> bool:
            return False

        async def wait_until_button_pressed(self, identifier: int) -> None:
            await anyio.sleep_forever()

    class QuickSuite(ButtonInterfaceConformance):
        call_timeout = 0.3

    subject = ButtonSubject(backend=Deaf(), identifiers=[0], press=nothing)
    with pytest.raises(Failed, match=r"did not finish within call_timeout \(0.3 s\)"):
        await run(QuickSuite, "test_wait_returns_after_a_press", subject)


# --- motors and servos ----------------------------------------------------------------


class ForgetfulMotors(MotorInterface):
    """One shared state for both motors, and BRAKE stored as 0."""

    def __init__(self) -> None:
        self.state: MotorState = MotorSpecialState.BRAKE

    async def get_motor_state(self, identifier: int) -> MotorState:
        check(identifier, 2)
        return self.state

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        check(identifier, 2)
        self.state = 0.0 if power is MotorSpecialState.BRAKE else power


async def test_motor_suite_catches_lost_states() -> None:
    subject = MotorSubject(backend=ForgetfulMotors(), identifiers=[0, 1])
    with pytest.raises(AssertionError, match=r"set to <MotorSpecialState.BRAKE: 1> but reads "
                                             "back 0.0"):
        await run(MotorInterfaceConformance, "test_brake_and_coast", subject)
    with pytest.raises(AssertionError, match=r"motor 1 was set to"):
        await run(MotorInterfaceConformance, "test_every_identifier", subject)


class HundredStepMotors(MotorInterface):
    """Motors a board drives in ±``steps`` steps (100 by default), rounded or truncated."""

    def __init__(
        self, *, brake_and_coast: bool = True, truncate: bool = False, steps: int = 100
    ) -> None:
        self.reported: dict[int, MotorState] = {0: 0.0, 1: 0.0}
        self.board_steps: dict[int, int] = {0: 0, 1: 0}
        self.brake_and_coast = brake_and_coast
        self.truncate = truncate
        self.steps = steps

    async def get_motor_state(self, identifier: int) -> MotorState:
        check(identifier, 2)
        return self.reported[identifier]  # what it was given, as many backends report

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        check(identifier, 2)
        if isinstance(power, MotorSpecialState):
            if not self.brake_and_coast:
                raise NotSupportedByHardwareError(f"this board has no {power.name}")
            self.reported[identifier] = power
            return
        steps = power * self.steps
        self.board_steps[identifier] = int(steps) if self.truncate else round(steps)
        self.reported[identifier] = power

    async def observe(self, identifier: int) -> MotorState:
        state = self.reported[identifier]
        if isinstance(state, MotorSpecialState):
            return state
        return self.board_steps[identifier] / self.steps


async def run_whole_suite(suite: Any, subject: Subject) -> list[str]:
    """Run every test of ``suite``; return the names of those that skipped."""
    skipped = []
    for name in dir(suite):
        if name.startswith("test_"):
            try:
                await run(suite, name, subject)
            except Skipped:
                skipped.append(name)
    return skipped


async def test_motor_suite_passes_a_board_without_brake_or_coast() -> None:
    backend = HundredStepMotors(brake_and_coast=False)
    subject = MotorSubject(
        backend=backend, identifiers=[0, 1], observe=backend.observe, special_states=(),
        power_step=0.01,
    )
    skipped = await run_whole_suite(MotorInterfaceConformance, subject)
    assert skipped == ["test_brake_and_coast", "test_every_hook_is_given"]  # no traffic hook


async def test_motor_suite_catches_a_board_that_lacks_a_declared_state() -> None:
    backend = HundredStepMotors(brake_and_coast=False)
    subject = MotorSubject(backend=backend, identifiers=[0, 1])
    with pytest.raises(NotSupportedByHardwareError):
        await run(MotorInterfaceConformance, "test_brake_and_coast", subject)


async def test_motor_suite_catches_an_undeclared_state_that_is_accepted() -> None:
    backend = HundredStepMotors(brake_and_coast=True)
    subject = MotorSubject(
        backend=backend, identifiers=[0, 1], special_states=[MotorSpecialState.BRAKE],
    )
    with pytest.raises(Failed, match="DID NOT RAISE"):
        await run(MotorInterfaceConformance, "test_undeclared_special_states_are_refused", subject)


async def test_motor_suite_catches_a_truncating_backend_through_observe() -> None:
    backend = HundredStepMotors(truncate=True)
    subject = MotorSubject(backend=backend, identifiers=[0, 1], observe=backend.observe)
    with pytest.raises(AssertionError, match=r"set to 0.667 but the board shows 0.66: is the"):
        await run(MotorInterfaceConformance, "test_the_board_shows_each_power", subject)
    with pytest.raises(AssertionError, match=r"set to 0.667 but the board shows 0.66"):
        await run(MotorInterfaceConformance, "test_set_then_get_round_trips", subject)
    rounding = HundredStepMotors(truncate=False)
    subject = MotorSubject(backend=rounding, identifiers=[0, 1], observe=rounding.observe)
    assert await run_whole_suite(MotorInterfaceConformance, subject) == [
        "test_every_hook_is_given",
        "test_undeclared_special_states_are_refused",
    ]


@pytest.mark.parametrize("steps", [100, 125, 127, 255, 1000])
async def test_motor_suite_catches_truncation_on_boards_of_every_common_step(steps: int) -> None:
    # Even at thousandths: int() where round() was meant shows on a 1000-step board.
    backend = HundredStepMotors(truncate=True, steps=steps)
    subject = MotorSubject(
        backend=backend, identifiers=[0, 1], observe=backend.observe, power_step=1 / steps,
    )
    with pytest.raises(AssertionError, match=r"is the power scaled, and rounded"):
        await run(MotorInterfaceConformance, "test_the_board_shows_each_power", subject)
    rounding = HundredStepMotors(steps=steps)
    subject = MotorSubject(
        backend=rounding, identifiers=[0, 1], observe=rounding.observe, power_step=1 / steps,
    )
    await run(MotorInterfaceConformance, "test_the_board_shows_each_power", subject)


async def test_motor_suite_without_observe_says_what_it_could_not_check() -> None:
    backend = HundredStepMotors(truncate=True)
    subject = MotorSubject(backend=backend, identifiers=[0, 1])
    with pytest.raises(Skipped, match="needs the 'observe' hook of the subject"):
        await run(MotorInterfaceConformance, "test_the_board_shows_each_power", subject)


def test_motor_and_servo_state_comparisons() -> None:
    assert same_state(0.5, 0.504, 0.01)
    assert not same_state(0.5, True, 0.01)
    assert not same_state(0.5, "0.5", 0.01)
    assert not same_state(MotorSpecialState.COAST, 0.0, 0.01)
    assert same_position(None, None, 0.01)
    assert not same_position(0.0, None, 0.01)
    assert not same_position(0.5, "0.5", 0.01)
    assert same_position(-1.0, -0.995, 0.01)


class StiffServos(ServoInterface):
    """Refuses to unpower a servo with the wrong error."""

    def __init__(self) -> None:
        self.positions: list[ServoPosition] = [0.0, 0.0]

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        check(identifier, 2)
        return self.positions[identifier]

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        check(identifier, 2)
        if position is None:
            raise ValueError("cannot unpower")
        self.positions[identifier] = position


async def test_servo_suite_catches_the_wrong_refusal_of_none() -> None:
    subject = ServoSubject(backend=StiffServos(), identifiers=[0, 1])
    with pytest.raises(ValueError, match=r"cannot unpower"):
        await run(ServoInterfaceConformance, "test_unpowered", subject)


# --- piezo, power outputs, battery ------------------------------------------------------


class BlockingPiezo(PiezoInterface):
    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        check(identifier, 1)
        await anyio.sleep(duration.total_seconds())


async def test_piezo_suite_catches_a_buzz_that_waits_for_the_note() -> None:
    class QuickSuite(PiezoInterfaceConformance):
        call_timeout = 0.2

    subject = PiezoSubject(backend=BlockingPiezo(), identifiers=[0])
    with pytest.raises(AssertionError, match=r"it must not wait for the note"):
        await run(QuickSuite, "test_buzz_returns_before_the_note_ends", subject)


async def test_piezo_suite_catches_wrong_notes() -> None:
    heard: list[tuple[timedelta, float]] = []

    class Detuned(PiezoInterface):
        async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
            heard.append((duration, pitch + 5))

    async def observe(identifier: int) -> list[tuple[timedelta, float]]:
        return heard

    subject = PiezoSubject(backend=Detuned(), identifiers=[0], observe=observe)
    with pytest.raises(AssertionError, match=r"asked for 440.0 Hz, the board played 445.0 Hz"):
        await run(PiezoInterfaceConformance, "test_the_board_plays_what_was_asked", subject)

    class Dropping(PiezoInterface):
        async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
            pass

    heard.clear()
    subject = PiezoSubject(backend=Dropping(), identifiers=[0], observe=observe)
    with pytest.raises(AssertionError, match=r"asked for 3 notes but played 0"):
        await run(PiezoInterfaceConformance, "test_the_board_plays_what_was_asked", subject)


class IntegerCurrents(PowerOutputInterface):
    def __init__(self) -> None:
        self.enabled = [False] * 2
        self.amps = [0.0] * 2

    async def get_power_output_enabled(self, identifier: int) -> bool:
        check(identifier, 2)
        return self.enabled[identifier]

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        check(identifier, 2)
        self.enabled[identifier] = enabled

    async def get_power_output_current(self, identifier: int) -> float:
        check(identifier, 2)
        return round(self.amps[identifier])


async def test_power_output_suite_catches_a_non_float_current() -> None:
    backend = IntegerCurrents()

    async def set_current(identifier: int, amps: float) -> None:
        backend.amps[identifier] = amps

    subject = PowerOutputSubject(backend=backend, identifiers=[0, 1], set_current=set_current)
    with pytest.raises(AssertionError, match=r"current read as 0, not a float"):
        await run(PowerOutputInterfaceConformance, "test_current_follows_the_load", subject)


async def test_power_output_suite_catches_a_board_that_did_not_switch() -> None:
    async def observe(identifier: int) -> bool:
        return False

    subject = PowerOutputSubject(backend=IntegerCurrents(), identifiers=[0, 1], observe=observe)
    with pytest.raises(AssertionError, match=r"output 0 was set to True but the board shows False"):
        await run(PowerOutputInterfaceConformance, "test_set_then_get_round_trips", subject)


class MillivoltBattery(BatterySensorInterface):
    def __init__(self) -> None:
        self.reading = (12.0, 1.0)

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        check(identifier, 1)
        return self.reading[0] * 1000

    async def get_battery_sensor_current(self, identifier: int) -> float:
        check(identifier, 1)
        return float("nan")


async def test_battery_suite_catches_wrong_units_and_nan() -> None:
    backend = MillivoltBattery()

    async def set_reading(identifier: int, volts: float, amps: float) -> None:
        backend.reading = (volts, amps)

    subject = BatterySensorSubject(backend=backend, identifiers=[0], set_reading=set_reading)
    with pytest.raises(AssertionError, match=r"battery 0 is at 12.0 V but reads 12000.0 V"):
        await run(BatterySensorInterfaceConformance, "test_readings_follow_the_battery", subject)
    with pytest.raises(AssertionError, match=r"not a finite number"):
        await run(BatterySensorInterfaceConformance, "test_readings_are_floats", subject)


# --- GPIO pins ----------------------------------------------------------------------------


class ReferencePins(GPIOPinInterface):
    def __init__(self) -> None:
        self.modes = {pin: GPIOPinMode.DIGITAL_INPUT for pin in range(3)}
        self.written = dict.fromkeys(range(3), False)
        self.inputs = dict.fromkeys(range(3), False)
        self.volts = dict.fromkeys(range(3), 0.0)
        self.pwm: list[tuple[int, float]] = []

    async def set_gpio_pin_mode(self, identifier: int, pin_mode: GPIOPinMode) -> None:
        check(identifier, 3)
        self.modes[identifier] = pin_mode

    async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
        check(identifier, 3)
        return self.modes[identifier]

    async def write_gpio_pin_digital_state(self, identifier: int, state: bool) -> None:
        check(identifier, 3)
        self.written[identifier] = state

    async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
        check(identifier, 3)
        return self.written[identifier]

    async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
        check(identifier, 3)
        return self.inputs[identifier]

    async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
        check(identifier, 3)
        return self.volts[identifier]

    async def write_gpio_pin_dac_value(self, identifier: int, scaled_value: float) -> None:
        check(identifier, 3)
        self.pwm.append((identifier, scaled_value))

    async def write_gpio_pin_pwm_value(self, identifier: int, duty_cycle: float) -> None:
        check(identifier, 3)
        self.pwm.append((identifier, duty_cycle))


ALL_MODES = frozenset(GPIOPinMode)


class TestReferencePins(GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        backend = ReferencePins()

        async def observe_output(identifier: int) -> bool:
            return backend.written[identifier]

        async def set_input(identifier: int, high: bool) -> None:
            backend.inputs[identifier] = high

        async def set_voltage(identifier: int, volts: float) -> None:
            backend.volts[identifier] = volts

        return GPIOPinSubject(
            backend=backend, identifiers=range(3), modes=dict.fromkeys(range(3), ALL_MODES),
            observe_output=observe_output, set_input=set_input, set_voltage=set_voltage,
        )


def pins_subject(backend: GPIOPinInterface, **hooks: Any) -> Any:
    return GPIOPinSubject(
        backend=backend, identifiers=range(3), modes=dict.fromkeys(range(3), ALL_MODES), **hooks,
    )


async def test_gpio_suite_catches_a_forgotten_write_and_a_wrong_mode() -> None:
    class Forgetful(ReferencePins):
        async def get_gpio_pin_digital_state(self, identifier: int) -> bool:
            return False

        async def get_gpio_pin_mode(self, identifier: int) -> GPIOPinMode:
            return GPIOPinMode.DIGITAL_INPUT

    subject = pins_subject(Forgetful())
    with pytest.raises(AssertionError, match=r"pin 0 was written True but reads back False"):
        await run(GPIOPinInterfaceConformance, "test_digital_write_is_remembered", subject)
    with pytest.raises(AssertionError, match=r"pin 0 was set to <GPIOPinMode.DIGITAL_INPUT_PULLUP"):
        await run(GPIOPinInterfaceConformance, "test_set_then_get_mode_round_trips", subject)


async def test_gpio_suite_catches_wrong_reads() -> None:
    class Inverted(ReferencePins):
        async def read_gpio_pin_digital_state(self, identifier: int) -> bool:
            return not self.inputs[identifier]

        async def read_gpio_pin_analogue_value(self, identifier: int) -> float:
            return self.volts[identifier] / 5

    backend = Inverted()

    async def set_input(identifier: int, high: bool) -> None:
        backend.inputs[identifier] = high

    async def set_voltage(identifier: int, volts: float) -> None:
        backend.volts[identifier] = volts

    subject = pins_subject(backend, set_input=set_input, set_voltage=set_voltage)
    with pytest.raises(AssertionError, match=r"pin 0 is at True but reads False"):
        await run(GPIOPinInterfaceConformance, "test_digital_read_follows_the_input", subject)
    with pytest.raises(AssertionError, match=r"pin 0 is at 1.25 V but reads 0.25 V"):
        await run(GPIOPinInterfaceConformance, "test_analogue_read_follows_the_voltage", subject)


async def test_gpio_suite_skips_what_no_pin_has() -> None:
    subject = GPIOPinSubject(backend=ReferencePins(), identifiers=range(3))
    assert subject.modes_of(1) == (GPIOPinMode.DIGITAL_OUTPUT,)
    with pytest.raises(Skipped, match=r"no pin of this board supports analogue input"):
        await run(GPIOPinInterfaceConformance, "test_analogue_read_is_a_float", subject)
    with pytest.raises(Skipped, match=r"no pin of this board supports digital input"):
        await run(GPIOPinInterfaceConformance, "test_digital_read_follows_the_input", subject)


# --- string commands and ultrasound --------------------------------------------------------


class RacyCommands(StringCommandComponentInterface):
    """Sends, then waits for 'the' reply: concurrent callers get each other's replies."""

    def __init__(self) -> None:
        self.last_reply = ""

    async def execute_string_command(self, command: str) -> str:
        self.last_reply = command.upper()
        await anyio.sleep(0.01)
        return self.last_reply


async def test_string_command_suite_catches_crossed_replies() -> None:
    exchanges = [("a", "A"), ("b", "B"), ("c", "C")]
    subject = StringCommandSubject(backend=RacyCommands(), exchanges=exchanges)
    await run(StringCommandInterfaceConformance, "test_each_command_gets_its_reply", subject)
    with pytest.raises(AssertionError, match=r"'a' should get 'A' but got 'C'"):
        await run(
            StringCommandInterfaceConformance,
            "test_concurrent_commands_get_their_own_replies",
            subject,
        )


class MillimetreUltrasound(UltrasoundInterface):
    def __init__(self) -> None:
        self.metres: float | None = 0.5

    async def get_ultrasound_pulse(self, trigger: int, echo: int) -> timedelta | None:
        check(trigger, 4)
        check(echo, 4)
        return None if self.metres is None else timedelta(seconds=self.metres / 343)

    async def get_ultrasound_distance(self, trigger: int, echo: int) -> float | None:
        check(trigger, 4)
        check(echo, 4)
        return 0.0 if self.metres is None else self.metres * 1000


async def test_ultrasound_suite_catches_wrong_units_and_echo_times() -> None:
    backend = MillimetreUltrasound()

    async def place_object(trigger: int, echo: int, metres: float | None) -> None:
        backend.metres = metres

    subject = UltrasoundSubject(
        backend=backend, identifiers=range(4), pairs=[(0, 1)], place_object=place_object,
    )
    with pytest.raises(AssertionError, match=r"object at 0.1 m reads as 100.0 m"):
        await run(UltrasoundInterfaceConformance, "test_readings_follow_the_object", subject)
    with pytest.raises(AssertionError, match=r"no object, but the distance reads 0.0"):
        await run(UltrasoundInterfaceConformance, "test_no_echo_reads_none", subject)
    await run(UltrasoundInterfaceConformance, "test_out_of_range_identifier_raises", subject)

    class Halved(MillimetreUltrasound):
        async def get_ultrasound_distance(self, trigger: int, echo: int) -> float | None:
            return self.metres

    halved = Halved()

    async def place(trigger: int, echo: int, metres: float | None) -> None:
        halved.metres = metres

    subject = UltrasoundSubject(backend=halved, pairs=[(0, 1)], place_object=place)
    with pytest.raises(AssertionError, match=r"object at 0.1 m gives a .* echo, which is 0.050 m"):
        await run(UltrasoundInterfaceConformance, "test_readings_follow_the_object", subject)


async def test_ultrasound_suite_catches_wrong_types() -> None:
    class Texty(MillimetreUltrasound):
        async def get_ultrasound_pulse(self, trigger: int, echo: int) -> timedelta | None:
            return 5  # type: ignore[return-value]

    subject = UltrasoundSubject(backend=Texty(), pairs=[(0, 1)])
    with pytest.raises(AssertionError, match=r"pulse read 5"):
        await run(UltrasoundInterfaceConformance, "test_readings_have_the_right_types", subject)
