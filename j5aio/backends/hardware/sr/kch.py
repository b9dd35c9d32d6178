"""The hardware backend of the KCH, the Raspberry Pi HAT of the SR 2023+ kit (GPIO, no firmware).

The LEDs hang on the Pi's GPIO pins (BCM numbers, high = lit): START 9; user LED A red,
green, blue 24, 10, 25; B 27, 23, 22; C 4, 18, 17. The HAT is recognised by its EEPROM,
which Linux shows under ``/sys/firmware/devicetree/base/hat/`` (vendor "Student
Robotics", product "KCH ...", asset code in ``custom_0``).

GPIO goes through `gpiozero <https://gpiozero.readthedocs.io>`_ and its pin factories,
chosen over using ``RPi.GPIO`` (what sr-robot3 uses) or ``lgpio`` / ``gpiod`` directly
because gpiozero is maintained by the Raspberry Pi community, is pure Python, picks
whichever pin library the Pi has (lgpio on current Raspberry Pi OS, RPi.GPIO on older
ones), flashes an LED in the background by itself, and ships a mock pin factory: the
simulated KCH (:mod:`j5aio.simulator.kch`) is this same backend over gpiozero's
``MockFactory``, so the simulation runs the real code. gpiozero imports without any GPIO
hardware; it is imported only when a KCH is opened, because it takes about 0.1 s.

Where there is no KCH (any computer other than a Pi with the HAT), discovery finds none
and :meth:`KCHHardwareBackend.open` raises a :class:`~j5aio.errors.CommunicationError`
that says so. gpiozero calls are short pin writes and run on the event loop.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.backend import Backend
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.boards.board import Board
from j5aio.boards.sr.kch import KCHBoard
from j5aio.components.flashing_led import FlashingLEDInterface, LEDMode
from j5aio.components.rgb_led import RGBChannel, RGBLEDInterface
from j5aio.errors import CommunicationError

if TYPE_CHECKING:
    from gpiozero import DigitalOutputDevice

__all__ = ["HAT_DIRECTORY", "KCH_PINS", "START_PIN", "HatInfo", "KCHHardwareBackend", "read_hat"]

_log = logging.getLogger(__name__)

#: The BCM pin of the start LED.
START_PIN: Final = 9
#: The BCM pins of user LEDs A, B and C, each (red, green, blue).
KCH_PINS: Final = ((24, 10, 25), (27, 23, 22), (4, 18, 17))
#: Where Linux shows the HAT EEPROM.
HAT_DIRECTORY: Final = Path("/sys/firmware/devicetree/base/hat")

_VENDOR: Final = "Student Robotics"
_PRODUCT_PREFIX: Final = "KCH"


# A frozen dataclass whose ``__init__`` is written here, the rest coming from FrozenRecord
# as ``@dataclass(frozen=True)`` would make it: every start of the kit imports this module,
# and making the generated methods costs a few hundred microseconds. A test checks it.
@frozen_record
class HatInfo(FrozenRecord):
    """What a HAT's EEPROM says about it."""

    vendor: str
    product: str
    asset_code: str

    def __init__(self, vendor: str, product: str, asset_code: str) -> None:
        set_field = object.__setattr__
        set_field(self, "vendor", vendor)
        set_field(self, "product", product)
        set_field(self, "asset_code", asset_code)


def read_hat(directory: Path = HAT_DIRECTORY) -> HatInfo | None:
    """Read the HAT EEPROM's strings; ``None`` if there is no HAT (or not a Pi)."""
    try:
        fields = [
            (directory / name).read_bytes().rstrip(b"\x00").decode("utf-8", "replace").strip()
            for name in ("vendor", "product", "custom_0")
        ]
    except OSError:
        return None
    return HatInfo(*fields)


def _is_kch(hat: HatInfo | None) -> bool:
    return hat is not None and hat.vendor == _VENDOR and hat.product.startswith(_PRODUCT_PREFIX)


class KCHHardwareBackend(RGBLEDInterface, FlashingLEDInterface, Backend):
    """Drives the KCH's LEDs through gpiozero.

    :param pin_factory: the gpiozero pin factory (``None``: gpiozero's default, the Pi's
        own GPIO).
    :raises CommunicationError: the pins cannot be used (no GPIO, or already in use).
    """

    board = KCHBoard

    #: The directory discovery reads the HAT EEPROM from.
    hat_directory: ClassVar[Path] = HAT_DIRECTORY
    #: Seconds for one on-and-off cycle of the flashing start LED.
    FLASH_PERIOD: ClassVar[float] = 1.0

    def __init__(self, pin_factory: Any = None) -> None:
        from gpiozero import DigitalOutputDevice, GPIOZeroError, PinFactoryFallback

        self._devices: list[DigitalOutputDevice] = []
        try:
            with warnings.catch_warnings():
                # gpiozero warns of each pin library it cannot load; the error below says it.
                warnings.simplefilter("ignore", PinFactoryFallback)
                self._start = self._output(DigitalOutputDevice, START_PIN, pin_factory)
                self._leds = tuple(
                    tuple(self._output(DigitalOutputDevice, pin, pin_factory) for pin in pins)
                    for pins in KCH_PINS
                )
        except GPIOZeroError as exc:
            self._close_devices()
            reason = str(exc).rstrip("!.")
            raise CommunicationError(
                f"cannot drive the {self.board.name}'s LEDs: {reason}. A KCH needs the GPIO of "
                "a Raspberry Pi (with lgpio or RPi.GPIO installed, as on Raspberry Pi OS).",
            ) from exc
        self._flashing = False

    def _output(self, device_class: type[DigitalOutputDevice], pin: int, factory: Any) -> Any:
        device = device_class(pin, initial_value=False, pin_factory=factory)
        self._devices.append(device)
        return device

    # -- making a backend ---------------------------------------------------------------

    @classmethod
    def from_pin_factory(cls, pin_factory: Any, serial_number: str) -> Board:
        """Drive a KCH on ``pin_factory``'s pins (a mock factory in the simulator)."""
        return cls.board(serial_number, cls(pin_factory))

    @classmethod
    def open(cls) -> Board:
        """Open the KCH of this Raspberry Pi.

        :raises CommunicationError: there is no KCH here, or its pins cannot be used.
        """
        hat = read_hat(cls.hat_directory)
        if hat is None or not _is_kch(hat):
            found = "no HAT" if hat is None else f"a {hat.vendor!r} {hat.product!r} HAT"
            raise CommunicationError(
                f"there is no KCH here: {cls.hat_directory} shows {found}. The KCH is the "
                "Student Robotics HAT of a Raspberry Pi; on any other computer use the "
                "simulated or console environment.",
            )
        return cls.from_pin_factory(None, hat.asset_code or "KCH")

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Return the KCH of this Raspberry Pi, or nothing where there is none.

        :param options: ignored (the KCH is not found on a serial port or USB); accepted
            so that listing can pass the same options to every backend.
        """
        if not _is_kch(read_hat(cls.hat_directory)):
            _log.info("No KCH: %s does not show a Student Robotics HAT.", cls.hat_directory)
            return []
        return [cls.open()]

    @property
    def firmware_version(self) -> None:
        """Always ``None``: the KCH has no firmware."""
        return None

    # -- LEDs ---------------------------------------------------------------------------

    @staticmethod
    def _check(kind: str, identifier: int, count: int) -> None:
        if isinstance(identifier, bool) or identifier not in range(count):
            raise ValueError(
                f"the KCH has {kind} 0 to {count - 1}, not {identifier!r}",
            )

    def _channel(self, identifier: int, channel: RGBChannel) -> Any:
        self._check("user LEDs", identifier, len(KCH_PINS))
        return self._leds[identifier][RGBChannel(channel)]

    async def get_rgb_led_channel_duty_cycle(self, identifier: int, channel: RGBChannel) -> float:
        """Return 1.0 if the pin of ``channel`` of user LED ``identifier`` is high, else 0.0."""
        return 1.0 if self._channel(identifier, channel).value else 0.0

    async def set_rgb_led_channel_duty_cycle(
        self,
        identifier: int,
        channel: RGBChannel,
        duty_cycle: float,
    ) -> None:
        """Light the channel fully for any duty cycle above 0, else darken it."""
        self._channel(identifier, channel).value = duty_cycle > 0

    async def get_led_state(self, identifier: int) -> bool:
        """Return whether the start LED is lit; a flashing LED counts as lit."""
        self._check("start LED", identifier, 1)
        return self._flashing or bool(self._start.value)

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or darken the start LED, stopping any flashing."""
        self._check("start LED", identifier, 1)
        self._start.value = state
        self._flashing = False

    async def get_led_mode(self, identifier: int) -> LEDMode:
        """Return whether the start LED is off, lit, or flashing."""
        self._check("start LED", identifier, 1)
        if self._flashing:
            return LEDMode.FLASH
        return LEDMode.ON if self._start.value else LEDMode.OFF

    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        """Light, darken, or flash the start LED.

        It flashes in the background (gpiozero's ``blink``), once every
        :attr:`FLASH_PERIOD` seconds.
        """
        self._check("start LED", identifier, 1)
        if mode is LEDMode.FLASH:
            half = self.FLASH_PERIOD / 2
            self._start.blink(on_time=half, off_time=half, background=True)
            self._flashing = True
        else:
            await self.set_led_state(identifier, mode is LEDMode.ON)

    # -- closing ------------------------------------------------------------------------

    def _close_devices(self) -> None:
        for device in self._devices:
            device.close()
        self._devices.clear()

    @property
    def closed(self) -> bool:
        """Whether the pins have been released."""
        return not self._devices

    def make_safe_now(self, timeout: float) -> bool:
        """Darken the start LED at once, synchronously (the safety net; see :class:`.Backend`).

        As :meth:`.KCHBoard.make_safe`: the user LEDs keep their colours. Stopping a
        flash joins gpiozero's blink thread, which ends at once when told.

        :returns: ``False`` once the pins have been released (nothing to darken).
        """
        if self.closed:
            return False
        self._start.off()
        self._flashing = False
        return True

    def close_now(self) -> None:
        """Stop flashing and release the pins, synchronously; idempotent."""
        self._flashing = False
        self._close_devices()

    async def close(self) -> None:
        """Stop flashing and release the pins.

        gpiozero makes a released pin an input (with lgpio and RPi.GPIO alike), so every
        LED, the user LEDs included, goes dark: a program's colours end with it.
        """
        self._flashing = False
        self._close_devices()
