import math
from collections.abc import Awaitable, Callable

import pytest

from j5aio.components import RGBLED, RGBChannel, RGBLEDInterface

from .component_fakes import RecordingBackend

Setter = Callable[[RGBLED, float], Awaitable[None]]
Getter = Callable[[RGBLED], Awaitable[float]]

CHANNELS: list[tuple[RGBChannel, Getter, Setter]] = [
    (RGBChannel.RED, RGBLED.get_red, RGBLED.set_red),
    (RGBChannel.GREEN, RGBLED.get_green, RGBLED.set_green),
    (RGBChannel.BLUE, RGBLED.get_blue, RGBLED.set_blue),
]


@pytest.mark.parametrize(("channel", "get", "set_"), CHANNELS)
async def test_each_channel_is_set_and_read(
    channel: RGBChannel, get: Getter, set_: Setter,
) -> None:
    backend = RecordingBackend()
    led = RGBLED(1, backend)

    await set_(led, 0.75)
    assert await get(led) == 0.75
    assert backend.duty == {c: 0.75 if c is channel else 0.0 for c in RGBChannel}
    assert backend.calls == [
        ("set_rgb_led_channel_duty_cycle", (1, channel, 0.75)),
        ("get_rgb_led_channel_duty_cycle", (1, channel)),
    ]


@pytest.mark.parametrize(("channel", "get", "set_"), CHANNELS)
@pytest.mark.parametrize("value", [-0.01, 1.5, math.nan])
async def test_each_channel_refuses_a_duty_cycle_outside_0_to_1(
    channel: RGBChannel, get: Getter, set_: Setter, value: float,
) -> None:
    backend = RecordingBackend()
    with pytest.raises(
        ValueError,
        match=rf"^RGB LED {channel.name.lower()} duty cycle must be a float between 0 "
        r"\(off\) and 1 \(full brightness\); got",
    ):
        await set_(RGBLED(0, backend), value)
    assert backend.calls == []


@pytest.mark.parametrize("value", [True, "1", None])
async def test_a_channel_refuses_a_duty_cycle_of_the_wrong_type(value: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=r"^RGB LED red duty cycle must be .*; got"):
        await RGBLED(0, backend).set_red(value)  # type: ignore[arg-type]
    assert backend.calls == []


async def test_set_colour_sets_every_channel_and_get_colour_reads_them() -> None:
    backend = RecordingBackend()
    led = RGBLED(2, backend)

    await led.set_colour((1, 0.5, 0))
    assert await led.get_colour() == (1.0, 0.5, 0.0)
    assert backend.calls == [
        ("set_rgb_led_channel_duty_cycle", (2, RGBChannel.RED, 1.0)),
        ("set_rgb_led_channel_duty_cycle", (2, RGBChannel.GREEN, 0.5)),
        ("set_rgb_led_channel_duty_cycle", (2, RGBChannel.BLUE, 0.0)),
        ("get_rgb_led_channel_duty_cycle", (2, RGBChannel.RED)),
        ("get_rgb_led_channel_duty_cycle", (2, RGBChannel.GREEN)),
        ("get_rgb_led_channel_duty_cycle", (2, RGBChannel.BLUE)),
    ]


async def test_set_colour_accepts_a_list() -> None:
    backend = RecordingBackend()
    await RGBLED(0, backend).set_colour([0.1, 0.2, 0.3])  # type: ignore[arg-type]
    assert backend.duty == {RGBChannel.RED: 0.1, RGBChannel.GREEN: 0.2, RGBChannel.BLUE: 0.3}


async def test_set_colour_checks_every_value_before_changing_any_channel() -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"^RGB LED blue duty cycle .* got 2"):
        await RGBLED(0, backend).set_colour((0.5, 0.5, 2))
    assert backend.calls == []


@pytest.mark.parametrize("colour", [(1, 1), (1, 1, 1, 1), ()])
async def test_set_colour_refuses_a_colour_without_three_values(colour: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"^RGB LED colour must be a \(red, green, blue\) tuple"):
        await RGBLED(0, backend).set_colour(colour)  # type: ignore[arg-type]
    assert backend.calls == []


@pytest.mark.parametrize("colour", ["rgb", 1.0, None, {1, 2, 3}])
async def test_set_colour_refuses_a_colour_of_the_wrong_type(colour: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=r"^RGB LED colour must be a \(red, green, blue\) tuple"):
        await RGBLED(0, backend).set_colour(colour)  # type: ignore[arg-type]
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    assert RGBLED(3, RecordingBackend()).identifier == 3
    assert RGBLED.interface_class() is RGBLEDInterface
