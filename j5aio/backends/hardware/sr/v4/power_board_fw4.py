r"""The hardware backend of the SR v4 Power Board, firmware 4.4 (USB CDC serial, text).

Discovery: serial ports with USB ID ``1BDA:0010`` (firmware 3 shares the ID but is a
control-transfer device, never a serial port), then the identity reply. Handshake:
``*IDN?`` → ``Student Robotics:PBv4B:<asset tag>:<version>`` (version 4.4 or 4.4.x,
else :class:`~j5aio.errors.UnsupportedFirmwareError`), then ``*RESET`` so the board
starts in its safe state. Everything is read from the board; the backend keeps no
cached state but the identity.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TYPE_CHECKING, ClassVar

import anyio

import j5aio.backends.hardware.sr.v4.power_fw4_codec as codec
from j5aio._timedelta import timedelta
from j5aio.backends.hardware.sr.v4.text_backend import SRTextBackend
from j5aio.backends.hardware.sr.v4.text_protocol import Identity, NackError
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4.power_board_fw4 import BoardResetInterface, PowerBoardFw4
from j5aio.components.battery_sensor import BatterySensorInterface
from j5aio.components.button import ButtonInterface
from j5aio.components.fan import FanInterface
from j5aio.components.flashing_led import FlashingLEDInterface, LEDMode
from j5aio.components.piezo import PiezoInterface
from j5aio.components.protected_power_output import ProtectedPowerOutputInterface
from j5aio.components.temperature_sensor import TemperatureSensorInterface
from j5aio.components.voltage_sensor import VoltageSensorInterface
from j5aio.errors import UnsupportedFirmwareError

if TYPE_CHECKING:
    from j5aio.backends.press_watch import PressWatch

__all__ = ["SRV4PowerBoardFw4HardwareBackend"]

_SUPPORTED = ("4.4", "4.4.<patch>")


class SRV4PowerBoardFw4HardwareBackend(
    ProtectedPowerOutputInterface,
    PiezoInterface,
    ButtonInterface,
    BatterySensorInterface,
    FlashingLEDInterface,
    TemperatureSensorInterface,
    FanInterface,
    VoltageSensorInterface,
    BoardResetInterface,
    SRTextBackend,
):
    """Drives an SR v4 Power Board running firmware 4.4."""

    board = PowerBoardFw4

    DEFAULT_TIMEOUT: ClassVar[float] = 0.5
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(codec.VID, codec.PID)})

    #: How often the button's latch is read while a task waits for a press, in seconds.
    BUTTON_POLL_INTERVAL: ClassVar[float] = 0.015

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        #: The identity the board gave in the handshake (the backend's only cached state).
        self.identity: Identity | None = None

    @property
    def asset_tag(self) -> str | None:
        """The asset tag the board reported, or ``None`` before the handshake."""
        return None if self.identity is None else self.identity.asset_tag

    async def _handshake(self, *, time_scale: float) -> None:
        try:
            reply = await self._query(codec.IDENTIFY)
        except NackError:
            # Leftovers of another program's (or kind's) probe, ahead of our line on a
            # port that does not reset when opened: the NACK ended them; ask again.
            reply = await self._query(codec.IDENTIFY)
        identity = codec.parse_identity_reply(self.board.name, reply)
        if not codec.is_supported_version(identity.version):
            raise UnsupportedFirmwareError(self.board.name, identity.version, _SUPPORTED)
        self.identity = identity
        self.firmware_version = identity.version
        await self._act(codec.RESET)

    async def _status(self) -> codec.PowerStatus:
        return codec.parse_status(self.board.name, await self._query(codec.STATUS))

    def make_safe_now(self, timeout: float) -> bool:
        """Reset the board at once, synchronously (the safety net; see :class:`.Backend`).

        ``*RESET`` is the board's safe state, as :meth:`.PowerBoardFw4.make_safe`: every
        output off but the brain's (L2), LEDs dark, the buzzer silent. A line ending goes
        first, so that a command cut in half by the program's end cannot swallow it; the
        replies are drained by the link before its next exchange.
        """
        if self._link.is_closed:
            return False
        self._link.send_now(b"\n" + codec.RESET, timeout=timeout)
        return True

    async def reset_board(self) -> None:
        """Reset the board (``*RESET``): outputs off but the brain's, LEDs off, silence."""
        await self._act(codec.RESET)

    # -- power outputs ------------------------------------------------------------------

    async def get_power_output_enabled(self, identifier: int) -> bool:
        """Read whether an output (0-6) is on."""
        command = codec.encode_output_get(identifier)
        return codec.parse_output_state(self.board.name, command, await self._query(command))

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Switch an output on or off (a tripped output stays off until the board resets).

        :raises NotSupportedByHardwareError: output 4 (L2) powers the brain; nothing is sent.
        """
        await self._act(codec.encode_output_set(identifier, enabled))

    async def get_power_output_current(self, identifier: int) -> float:
        """Read the current an output draws, in amperes (output 6: the 5 V rail)."""
        command = codec.encode_output_current(identifier)
        return codec.parse_current_ma(self.board.name, command, await self._query(command)) / 1000

    async def get_power_output_overcurrent(self, identifier: int) -> bool:
        """Read whether an output is latched off by its over-current trip (``*STATUS?``)."""
        codec.check_output(identifier)
        return (await self._status()).overcurrent[identifier]

    # -- piezo --------------------------------------------------------------------------

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Play a note now, replacing any note playing (the board keeps no queue).

        :raises NotSupportedByHardwareError: outside 8-10000 Hz, or under 1 ms.
        """
        self._check_single(identifier, "piezo")
        # Not sent again after a reconnection: a note that already played must not repeat.
        await self._act(codec.encode_note(duration, pitch), idempotent=False)

    # -- start button -------------------------------------------------------------------

    async def get_button_state(self, identifier: int) -> bool:
        """Return whether a start button was pressed since the last read (the board latches)."""
        self._check_single(identifier, "start button")
        return codec.parse_button(self.board.name, await self._query(codec.BUTTON)).pressed

    @functools.cached_property
    def _presses(self) -> PressWatch:
        """The start button's presses, watched for every waiter (made at the first wait).

        (Its module is imported then: a program that never waits for the button, or
        waits only at match time, does not load it at start.)
        """
        from j5aio.backends.press_watch import PressWatch

        return PressWatch(self._poll_button)

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Return once a start button is pressed; a press before the wait does not count.

        However many tasks wait, one poll stream reads the board (see
        :class:`~j5aio.backends.press_watch.PressWatch`): when the first waiter comes,
        the latch is read once and forgotten, then read every 15 ms. The board latches
        presses, so none is lost between reads.
        """
        if identifier != 0:
            self._check_single(identifier, "start button")  # raises
        await self._presses.wait()

    async def _poll_button(self, report: Callable[[], None], *, fresh: bool) -> None:
        def latched(reply: bytes) -> bool:
            # Runs as the reply arrives, even for a cancelled leader: a latched press,
            # which the read has just cleared on the board, is never dropped.
            pressed = codec.parse_button(self.board.name, reply).pressed
            if pressed:
                report()
            return pressed

        if fresh:
            await self._query(codec.BUTTON)  # a press from before anyone waited
        while not await self._query_then(codec.BUTTON, latched):  # noqa: ASYNC110 - a board
            await anyio.sleep(self.BUTTON_POLL_INTERVAL)

    # -- battery ------------------------------------------------------------------------

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        """Read the battery voltage, in volts."""
        self._check_single(identifier, "battery sensor")
        reply = await self._query(codec.BATTERY_VOLTAGE)
        return codec.parse_current_ma(self.board.name, codec.BATTERY_VOLTAGE, reply) / 1000

    async def get_battery_sensor_current(self, identifier: int) -> float:
        """Read the battery current, in amperes (negative while it charges)."""
        self._check_single(identifier, "battery sensor")
        reply = await self._query(codec.BATTERY_CURRENT)
        milliamps = codec.parse_current_ma(
            self.board.name,
            codec.BATTERY_CURRENT,
            reply,
            signed=True,
        )
        return milliamps / 1000

    # -- LEDs ---------------------------------------------------------------------------

    async def get_led_mode(self, identifier: int) -> LEDMode:
        """Read whether LED 0 (run) or 1 (error) is off, on or flashing."""
        command = codec.encode_led_get(identifier)
        return codec.parse_led_mode(self.board.name, command, await self._query(command))

    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        """Switch LED 0 (run) or 1 (error) off, on, or to flashing (once a second)."""
        await self._act(codec.encode_led_set(identifier, mode))

    async def get_led_state(self, identifier: int) -> bool:
        """Read whether an LED is lit or flashing."""
        return await self.get_led_mode(identifier) is not LEDMode.OFF

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light or darken an LED (which stops it flashing)."""
        await self.set_led_mode(identifier, LEDMode.ON if state else LEDMode.OFF)

    # -- status -------------------------------------------------------------------------

    async def get_temperature(self, identifier: int) -> float:
        """Read the board's temperature, in °C (``*STATUS?``)."""
        self._check_single(identifier, "temperature sensor")
        return float((await self._status()).temperature)

    async def get_fan_running(self, identifier: int) -> bool:
        """Read whether the fan runs (``*STATUS?``)."""
        self._check_single(identifier, "fan")
        return (await self._status()).fan

    async def get_voltage_sensor_voltage(self, identifier: int) -> float:
        """Read the 5 V regulator's voltage, in volts (``*STATUS?``)."""
        self._check_single(identifier, "voltage sensor")
        return (await self._status()).regulator_mv / 1000
