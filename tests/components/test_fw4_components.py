"""The components added for today's kits: PulseServo, SupplySensor, Flag and FlashingLED."""


import pytest

from j5aio.components import (
    Flag,
    FlagInterface,
    FlashingLED,
    FlashingLEDInterface,
    PulseLimits,
    PulseServo,
    PulseServoInterface,
    ServoPosition,
    SupplySensor,
    SupplySensorInterface,
)
from j5aio.components.flashing_led import LEDMode

Call = tuple[str, tuple[object, ...]]


class Recorder(PulseServoInterface, SupplySensorInterface, FlagInterface, FlashingLEDInterface):
    def __init__(self) -> None:
        self.calls: list[Call] = []
        self.limits: PulseLimits = (1000, 2000)

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        self.calls.append(("get_servo_position", (identifier,)))
        return 0.5

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        self.calls.append(("set_servo_position", (identifier, position)))

    async def get_servo_pulse_range(self, identifier: int) -> PulseLimits:
        self.calls.append(("get_servo_pulse_range", (identifier,)))
        return (500, 4000)

    async def get_servo_pulse_limits(self, identifier: int) -> PulseLimits:
        self.calls.append(("get_servo_pulse_limits", (identifier,)))
        return self.limits

    async def set_servo_pulse_limits(self, identifier: int, limits: PulseLimits) -> None:
        self.calls.append(("set_servo_pulse_limits", (identifier, limits)))
        self.limits = limits

    async def get_servo_pulse_width(self, identifier: int) -> int | None:
        self.calls.append(("get_servo_pulse_width", (identifier,)))
        return 1495

    async def get_supply_voltage(self, identifier: int) -> float:
        self.calls.append(("get_supply_voltage", (identifier,)))
        return 5.5

    async def get_supply_current(self, identifier: int) -> float:
        self.calls.append(("get_supply_current", (identifier,)))
        return 0.25

    async def get_flag_state(self, identifier: int) -> bool:
        self.calls.append(("get_flag_state", (identifier,)))
        return identifier == 1

    async def get_led_state(self, identifier: int) -> bool:
        self.calls.append(("get_led_state", (identifier,)))
        return False

    async def set_led_state(self, identifier: int, state: bool) -> None:
        self.calls.append(("set_led_state", (identifier, state)))

    async def get_led_mode(self, identifier: int) -> LEDMode:
        self.calls.append(("get_led_mode", (identifier,)))
        return LEDMode.FLASH

    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        self.calls.append(("set_led_mode", (identifier, mode)))


def test_interfaces() -> None:
    assert PulseServo.interface_class() is PulseServoInterface
    assert SupplySensor.interface_class() is SupplySensorInterface
    assert Flag.interface_class() is FlagInterface
    assert FlashingLED.interface_class() is FlashingLEDInterface


async def test_pulse_servo_limits_are_checked_against_the_range() -> None:
    backend = Recorder()
    servo = PulseServo(4, backend)
    await servo.set_pulse_limits(500, 4000)
    assert backend.calls[-1] == ("set_servo_pulse_limits", (4, (500, 4000)))
    assert await servo.get_pulse_limits() == (500, 4000)
    assert await servo.get_pulse_range() == (500, 4000)
    assert await servo.get_pulse_width() == 1495
    assert await servo.get_position() == 0.5
    await servo.set_position(None)
    assert backend.calls[-1:] == [("set_servo_position", (4, None))]


@pytest.mark.parametrize(
    ("lower", "upper", "error"),
    [(499, 2000, ValueError), (1000, 4001, ValueError), (2000, 2000, ValueError),
     (2000, 1000, ValueError), ("1000", 2000, TypeError), (1000, 2000.5, TypeError),
     (False, 2000, TypeError)],
)
async def test_pulse_servo_refuses_bad_limits_without_setting(
    lower: object, upper: object, error: type[Exception],
) -> None:
    backend = Recorder()
    with pytest.raises(error, match="pulse limit"):
        await PulseServo(0, backend).set_pulse_limits(lower, upper)  # type: ignore[arg-type]
    assert all(name != "set_servo_pulse_limits" for name, _ in backend.calls)


async def test_supply_and_flags() -> None:
    backend = Recorder()
    assert await SupplySensor(0, backend).get_voltage() == 5.5
    assert await SupplySensor(0, backend).get_current() == 0.25
    assert await Flag(0, backend).get_state() is False
    assert await Flag(1, backend).get_state() is True
    assert backend.calls == [
        ("get_supply_voltage", (0,)), ("get_supply_current", (0,)),
        ("get_flag_state", (0,)), ("get_flag_state", (1,)),
    ]


async def test_flashing_led() -> None:
    backend = Recorder()
    led = FlashingLED(0, backend)
    await led.flash()
    assert await led.get_mode() is LEDMode.FLASH
    await led.set_state(True)
    assert backend.calls == [
        ("set_led_mode", (0, LEDMode.FLASH)),
        ("get_led_mode", (0,)), ("set_led_state", (0, True)),
    ]
