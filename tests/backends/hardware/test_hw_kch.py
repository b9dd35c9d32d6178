from pathlib import Path

import anyio
import pytest
from gpiozero.pins.mock import MockFactory

from j5aio.backends.hardware.sr.kch import (
    KCH_PINS,
    START_PIN,
    HatInfo,
    KCHHardwareBackend,
    read_hat,
)
from j5aio.boards.sr.kch import Colour, KCHBoard
from j5aio.components.flashing_led import LEDMode
from j5aio.components.rgb_led import RGBChannel
from j5aio.errors import CommunicationError
from tests.dataclass_twins import assert_like_generated


def make_hat(directory: Path, vendor: str, product: str, asset: str) -> Path:
    directory.mkdir()
    for name, value in (("vendor", vendor), ("product", product), ("custom_0", asset)):
        (directory / name).write_bytes(value.encode() + b"\x00")
    return directory


async def kch(factory: MockFactory) -> KCHBoard:
    board = KCHHardwareBackend.from_pin_factory(factory, "SR0K")
    assert isinstance(board, KCHBoard)
    await board.setup()
    return board


def test_pins_are_those_of_the_protocol() -> None:
    assert START_PIN == 9
    assert KCH_PINS == ((24, 10, 25), (27, 23, 22), (4, 18, 17))


async def test_user_leds_drive_their_pins() -> None:
    factory = MockFactory()
    board = await kch(factory)
    assert board.firmware_version is None
    assert all(not factory.pin(pin).state for pins in KCH_PINS for pin in pins)
    await board.leds[2].set_colour(Colour.YELLOW)
    assert (factory.pin(4).state, factory.pin(18).state, factory.pin(17).state) == (1, 1, 0)
    assert await board.leds[2].get_colour() == Colour.YELLOW
    await board.leds[0].set_blue(0.1)  # any brightness lights a part fully
    assert factory.pin(25).state
    assert await board.leds[0].get_blue() == 1.0
    await board.leds[0].set_blue(0)
    assert not factory.pin(25).state
    await board.close()


async def test_start_led_flashes_in_the_background_until_set(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    factory = MockFactory()
    board = await kch(factory)
    monkeypatch.setattr(KCHHardwareBackend, "FLASH_PERIOD", 0.04)
    await board.start_led.flash()
    assert await board.start_led.get_mode() is LEDMode.FLASH
    with anyio.fail_after(5):
        while len(factory.pin(START_PIN).states) < 5:  # noqa: ASYNC110 - a thread toggles it
            await anyio.sleep(0.01)
    await board.start_led.set_state(True)
    assert await board.start_led.get_mode() is LEDMode.ON
    assert factory.pin(START_PIN).state
    assert await board.start_led.get_state()
    await board.make_safe()
    assert not factory.pin(START_PIN).state
    await board.close()


async def test_identifiers_are_checked() -> None:
    board = await kch(MockFactory())
    backend = board.backend
    assert isinstance(backend, KCHHardwareBackend)
    with pytest.raises(ValueError, match="user LEDs 0 to 2"):
        await backend.set_rgb_led_channel_duty_cycle(3, RGBChannel.RED, 1.0)
    with pytest.raises(ValueError, match="start LED 0 to 0"):
        await backend.get_led_state(1)
    with pytest.raises(ValueError, match="start LED"):
        await backend.set_led_mode(True, LEDMode.FLASH)
    await board.close()


def test_read_hat(tmp_path: Path) -> None:
    assert read_hat(tmp_path / "missing") is None
    hat = make_hat(tmp_path / "hat", "Student Robotics", "KCH V1 Rev B", "SR0ABC")
    assert read_hat(hat) == HatInfo("Student Robotics", "KCH V1 Rev B", "SR0ABC")


async def test_without_a_kch_discovery_finds_none_and_open_says_so(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(KCHHardwareBackend, "hat_directory", tmp_path / "missing")
    assert await KCHHardwareBackend.discover() == []
    with pytest.raises(CommunicationError, match=r"there is no KCH here: .* shows no HAT"):
        KCHHardwareBackend.open()
    other = make_hat(tmp_path / "hat", "Pimoroni", "Fan SHIM", "")
    monkeypatch.setattr(KCHHardwareBackend, "hat_directory", other)
    assert await KCHHardwareBackend.discover() == []
    with pytest.raises(CommunicationError, match="'Pimoroni' 'Fan SHIM' HAT"):
        KCHHardwareBackend.open()


async def test_a_kch_without_usable_gpio_is_a_clear_error(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    hat = make_hat(tmp_path / "hat", "Student Robotics", "KCH V1 Rev B", "SR0ABC")
    monkeypatch.setattr(KCHHardwareBackend, "hat_directory", hat)
    factory = MockFactory()
    factory.pin(START_PIN)  # a pin already in use elsewhere
    blocker = KCHHardwareBackend(factory)  # holds every pin
    with pytest.raises(CommunicationError, match="cannot drive the Student Robotics KCH's LEDs"):
        KCHHardwareBackend(factory)
    await blocker.close()

    # This machine has no GPIO (CI and developers' machines are not Raspberry Pis).
    with pytest.raises(CommunicationError, match="GPIO of a Raspberry Pi"):
        await KCHHardwareBackend.discover()


async def test_make_safe_now_darkens_the_start_led_synchronously(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    factory = MockFactory()
    board = await kch(factory)
    backend = board.backend
    assert isinstance(backend, KCHHardwareBackend)
    monkeypatch.setattr(KCHHardwareBackend, "FLASH_PERIOD", 0.04)
    await board.leds[0].set_colour(Colour.RED)
    await board.start_led.flash()
    assert backend.make_safe_now(0.5) is True
    assert await board.start_led.get_mode() is LEDMode.OFF
    assert not factory.pin(START_PIN).state
    assert factory.pin(24).state  # the user LEDs keep their colours
    backend.close_now()
    assert backend.closed
    assert backend.make_safe_now(0.5) is False
    backend.close_now()  # idempotent
    await board.close()


def test_hat_info_is_the_generated_dataclass() -> None:
    assert_like_generated(
        HatInfo,
        [
            (("Student Robotics", "KCH V1 Rev B", "SR0ABC"), {}),
            (("Student Robotics", "KCH V1 Rev B", "SR0ABD"), {}),
            ((), {"vendor": "Other", "product": "HAT", "asset_code": ""}),
        ],
    )
