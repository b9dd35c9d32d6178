"""The hardware backend of the SR v4 Power Board, firmware 3 (USB control transfers).

Handshake: one read of ``wIndex`` 9 (4 bytes), which must be 3. The outputs and LEDs
cannot be read back, so their states are the ones last written; at first they are the
board's power-up state: outputs off, RUN LED on, ERROR LED off (cleared when the host
enumerates the board).
"""

from __future__ import annotations

import functools
import time
from collections.abc import Awaitable, Callable
from typing import TYPE_CHECKING, ClassVar

import j5aio.backends.hardware.sr.v4.power_fw3_codec as codec
from j5aio.backends.hardware.transports.usb_link import USBLink
from j5aio.backends.hardware.usb_backend import USBHardwareBackend
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.components.battery_sensor import BatterySensorInterface
from j5aio.components.button import ButtonInterface
from j5aio.components.led import LEDInterface
from j5aio.components.piezo import PiezoInterface
from j5aio.components.power_output import PowerOutputInterface
from j5aio.errors import BoardDisconnectionError, UnsupportedFirmwareError

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta
    from j5aio.backends.press_watch import PressWatch

__all__ = ["SRV4PowerBoardHardwareBackend"]

#: Whether a reply to :data:`~.power_fw3_codec.BUTTON` says the button is down: any
#: value but zero (``parse_u32(reply) != 0``, which the poll has checked is 4 bytes long).
#: A C comparison with no Python frame, since it runs on every poll (see
#: :meth:`.USBLink.poll_until`).
_button_held: Callable[[bytes], bool] = bytes(codec.BUTTON.length).__ne__

_PIEZO_ERRORS = {
    32: "the piezo queue is full: buzz commands were sent too quickly (the board holds "
    f"{codec.PIEZO_QUEUE_LENGTH} notes). Wait for notes to finish, or buzz with blocking=True",
}


class SRV4PowerBoardHardwareBackend(
    PowerOutputInterface,
    PiezoInterface,
    ButtonInterface,
    BatterySensorInterface,
    LEDInterface,
    USBHardwareBackend,
):
    """Drives an SR v4 Power Board running firmware 3."""

    board = PowerBoard
    VID: ClassVar[int] = codec.VID
    PID: ClassVar[int] = codec.PID

    # Firmware 4 (same IDs) is a CDC serial device, found through its serial port.
    SINGLE_INTERFACE: ClassVar[bool] = True

    #: How often the button is read while a task waits for a press, in seconds. A read
    #: runs on the link's worker thread and wakes the event loop only once it sees the
    #: button down (see :meth:`.USBLink.poll_until`), so an idle read costs one wake-up
    #: of that thread and the transfer. Chosen with ``bench/bench_button.py
    #: --intervals``: a press waits half an interval on average (measured p50 7.6 ms,
    #: p95 14.4 ms; goals 10 and 20 ms) for about 1 % CPU on a loaded machine. A longer
    #: interval saves little CPU there: each read after a longer sleep finds the caches
    #: colder and costs more (15-17 ms all measured 1.07 %).
    BUTTON_POLL_INTERVAL: ClassVar[float] = 0.015

    def __init__(self, link: USBLink, *, key: str) -> None:
        super().__init__(link, key=key)
        self._outputs = [False] * codec.OUTPUT_COUNT
        self._leds = [True, False]

    def reset_board_state(self) -> None:
        """Forget what was remembered: the board is at its power-up state again."""
        self._outputs = [False] * codec.OUTPUT_COUNT
        self._leds = [True, False]

    async def _handshake(self) -> None:
        version = str(codec.parse_u32(await self._read_command(codec.FIRMWARE_VERSION)))
        if version not in codec.SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, codec.SUPPORTED_VERSIONS)
        self.firmware_version = version

    async def _read_command(self, command: codec.ReadCommand) -> bytes:
        return await self.control_read(command.index, command.length)

    # -- power outputs ------------------------------------------------------------------

    def _check_output(self, identifier: int) -> None:
        codec.check_output(identifier)

    async def get_power_output_enabled(self, identifier: int) -> bool:
        """Return whether an output was last switched on (the board cannot report it)."""
        self._check_output(identifier)
        return self._outputs[identifier]

    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Switch an output on or off."""
        self._check_output(identifier)

        def remember() -> None:
            self._outputs[identifier] = enabled

        await self.control_write(identifier, int(enabled), then=remember)

    def make_safe_now(self, timeout: float) -> bool:
        """Switch every output off at once, synchronously (the safety net; see :class:`.Backend`).

        ``timeout`` bounds the whole, shared between the outputs.
        """
        if self._link.is_closed:
            return False
        deadline = time.monotonic() + timeout
        for output in range(codec.OUTPUT_COUNT):
            left = max(deadline - time.monotonic(), 0.001)
            self._link.control_write_now(output, 0, timeout=left)
            self._outputs[output] = False
        return True

    async def get_power_output_current(self, identifier: int) -> float:
        """Read the current an output draws, in amperes."""
        command = codec.output_current_read(identifier)
        return codec.parse_u32(await self._read_command(command)) / 1000

    # -- piezo --------------------------------------------------------------------------

    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Queue a note on the piezo (it plays after the notes already queued).

        :raises NotSupportedByHardwareError: over 65535 Hz or 65535 ms.
        :raises CommunicationError: the board's queue of notes is full.
        """
        self._check_single(identifier, "piezo")
        note = codec.encode_piezo_note(duration, pitch)
        # Not idempotent: a note sent again after the board came back would play twice.
        await self.control_write(codec.PIEZO_WRITE, 0, note, errors=_PIEZO_ERRORS, idempotent=False)

    # -- start button -------------------------------------------------------------------

    async def get_button_state(self, identifier: int) -> bool:
        """Return whether the start button is held down now (it is not latched)."""
        self._check_single(identifier, "button")
        return codec.parse_u32(await self._read_command(codec.BUTTON)) != 0

    @functools.cached_property
    def _presses(self) -> PressWatch:
        """The start button's presses, watched for every waiter (made at the first wait).

        (Its module is imported then: a program that never waits for the button, or
        waits only at match time, does not load it at start.)
        """
        from j5aio.backends.press_watch import PressWatch

        return PressWatch(self._poll_button)

    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Return once the start button is seen down (read every 15 ms while anyone waits).

        However many tasks wait, the board is read by one poll stream (see
        :class:`~j5aio.backends.press_watch.PressWatch`).
        """
        if identifier != 0:
            self._check_single(identifier, "button")  # raises
        await self._presses.wait()

    async def _poll_button(self, report: Callable[[], None], *, fresh: bool) -> None:
        # The button is a level, not a latch: ``fresh`` has nothing to forget.
        def poll() -> Awaitable[bytes]:  # the link is looked up anew for a retry
            return self._link.poll_control_read(
                codec.BUTTON.index,
                codec.BUTTON.length,
                _button_held,
                interval=self.BUTTON_POLL_INTERVAL,
                then=lambda _reply: report(),
            )

        try:  # the steps of _guarded, written out: one call fewer to the first poll
            if self._lost or self._closed_for_good:
                await self._check_connected()
            await self._link.poll_control_read(
                codec.BUTTON.index,
                codec.BUTTON.length,
                _button_held,
                interval=self.BUTTON_POLL_INTERVAL,
                then=lambda _reply: report(),
            )
        except BoardDisconnectionError as error:
            await self._retry_after(error, poll, idempotent=True)

    # -- battery ------------------------------------------------------------------------

    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        """Read the battery voltage, in volts."""
        self._check_single(identifier, "battery sensor")
        return codec.parse_battery(await self._read_command(codec.BATTERY)).voltage

    async def get_battery_sensor_current(self, identifier: int) -> float:
        """Read the battery current, in amperes."""
        self._check_single(identifier, "battery sensor")
        return codec.parse_battery(await self._read_command(codec.BATTERY)).current

    # -- LEDs ---------------------------------------------------------------------------

    async def get_led_state(self, identifier: int) -> bool:
        """Return the state last written to an LED (the board cannot report it)."""
        codec.check_led(identifier)
        return self._leds[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light (``True``) or clear LED 0 (run) or 1 (error)."""
        index = codec.led_write_index(identifier)

        def remember() -> None:
            self._leds[identifier] = state

        await self.control_write(index, int(state), then=remember)
