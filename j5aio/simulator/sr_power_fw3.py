"""Simulator of the SR Power Board v4 running firmware 3 (USB control transfers).

Protocol (:doc:`/internals/sr-power-board`): every request is ``bRequest`` 64, standard type, device
recipient; the command is in ``wIndex``.

Reads (``bmRequestType`` 0x80), all little-endian ``uint32``:

====== ======== ===================================================
wIndex wLength  reply
====== ======== ===================================================
0-5    >= 4     current of output n in mA
6      >= 4     5 V rail: not measured by fw 3, the buffer's stale bytes
7      >= 8     battery current (mA) then battery voltage (mV)
8      >= 4     start button level (1 while held, not latched)
9      >= 4     firmware version, 3
====== ======== ===================================================

Writes (``bmRequestType`` 0x00): wIndex 0-5 switch output n (wValue 0 = off), 6 the RUN
LED, 7 the ERROR LED, 8 queue piezo notes (payload of ``<HH`` (Hz, ms) samples).

The piezo plays its queue on the firmware's clock (:mod:`j5aio.simulator.clock`): a
simulated kit's, which runs in real or scaled time, or, for a board made on its own, a
manual clock that stands still until moved on. The queue is brought up to date whenever
it is read or a request arrives.

Stalls: any other request or wIndex, a read with too small a wLength, a piezo payload that
is empty, not a multiple of 4 bytes, or longer than the room left in the 31-note queue.
"""

from __future__ import annotations

import struct
from collections import deque
from typing import ClassVar, Final, NamedTuple

from .clock import BoardTime, Clock
from .loads import PowerBoardLoads
from .sr_usb import SRUsbBoardSimulator
from .usb_support import UsbStall

__all__ = ["PiezoNote", "SRPowerBoardFw3Simulator"]

_U32: Final = struct.Struct("<I")
_BATTERY: Final = struct.Struct("<II")
_SAMPLE: Final = struct.Struct("<HH")

_READ_OUTPUT_LAST: Final = 5
_READ_5V_RAIL: Final = 6
_READ_BATTERY: Final = 7
_READ_BUTTON: Final = 8
_READ_VERSION: Final = 9

_WRITE_OUTPUT_LAST: Final = 5
_WRITE_RUN_LED: Final = 6
_WRITE_ERROR_LED: Final = 7
_WRITE_PIEZO: Final = 8

_RING_SLOTS: Final = 32  # the firmware's ring buffer; one slot always stays empty
_MAX_FREQUENCY: Final = 10_000
_UNDERVOLTAGE_MV: Final = 10_200  # output drivers start only above this at boot
_BATTERY_OFFSET_MA: Final = 800  # the INA219 reads this much high; the firmware subtracts it
_SHUNT_STEP_MA: Final = 20  # one 10 µV shunt-register step over the 0.5 mΩ sense resistor
_BUS_STEP_MV: Final = 4
_BUS_MAX_MV: Final = 0x1FFF * _BUS_STEP_MV


class PiezoNote(NamedTuple):
    """One piezo sample as the host queued it."""

    frequency: int
    """Frequency in Hz as sent; 0 is a rest."""
    duration_ms: int
    """Duration in milliseconds."""

    @property
    def played_frequency(self) -> int:
        """The frequency the buzzer actually plays: capped at 10 kHz, 0 for a rest."""
        return min(self.frequency, _MAX_FREQUENCY)


class SRPowerBoardFw3Simulator(PowerBoardLoads, SRUsbBoardSimulator):
    """An SR Power Board v4 with firmware 3, seen through pyusb.

    The board starts powered up, enumerated (RUN LED on, ERROR LED off), with all outputs
    off and a 12 V battery, so its output drivers are running. Queued notes play out on
    the board's clock (:meth:`use_clock`; :meth:`advance_piezo` lets more time pass).
    """

    idVendor: ClassVar[int] = 0x1BDA  # noqa: N815
    idProduct: ClassVar[int] = 0x0010  # noqa: N815
    bcdDevice: ClassVar[int] = 0x0403  # noqa: N815
    #: The firmware version this board reports.
    version: ClassVar[int] = 3
    #: Number of switchable outputs (H0, H1, L0, L1, L2, L3).
    OUTPUT_COUNT: ClassVar[int] = 6
    #: How many piezo notes the queue holds, counting the one playing.
    NOTE_QUEUE_CAPACITY: ClassVar[int] = _RING_SLOTS - 1

    def __init__(
        self,
        serial_number: str | None,
        *,
        battery_voltage: float = 12.0,
        battery_current: float = 0.0,
    ) -> None:
        super().__init__(serial_number, manufacturer="Student Robotics", product="Power board v4")
        self._start_loads(battery_voltage)
        self.battery_current = battery_current
        self._output_ma = [0] * self.OUTPUT_COUNT
        self._internal_button = False
        self._external_button = False
        self._outputs = [False] * self.OUTPUT_COUNT
        self._trips = [False] * self.OUTPUT_COUNT
        self._run_led = True
        self._error_led = True
        self._notes: deque[PiezoNote] = deque()
        self._note_elapsed_ms = 0
        self._time = BoardTime()
        self._piezo_ms = 0  # the board's time the piezo queue was brought up to
        self._drivers_ready = False
        self.power_cycle()

    # --- board life cycle ---

    def power_cycle(self) -> None:
        """Switch the board off and on again.

        All outputs off, trips cleared, piezo queue emptied, RUN and ERROR LEDs lit; the
        output drivers start only if the battery is above 10.2 V now. If the board is
        plugged in the host enumerates it, which turns the ERROR LED off.
        """
        self._control_buffer[:] = bytes(len(self._control_buffer))
        self._reset_callback()
        self._drivers_ready = self._battery_mv > _UNDERVOLTAGE_MV
        if self.connected:
            self._enumerated()
        self._tell_listeners()

    def bus_reset(self) -> None:
        """Reset the USB bus and enumerate again, as a host does when it re-enumerates.

        The firmware switches every output off, clears the trips, stops the piezo and lights
        both LEDs; enumeration then turns the ERROR LED off.
        """
        self._reset_callback()
        self._enumerated()
        self._tell_listeners()

    def _reset_callback(self) -> None:
        self._outputs = [False] * self.OUTPUT_COUNT
        self._trips = [False] * self.OUTPUT_COUNT
        self._stop_piezo()
        self._run_led = True
        self._error_led = True

    def _enumerated(self) -> None:
        self._error_led = False

    def plug(self) -> None:
        """Plug the USB cable back in: the host resets the bus and enumerates the board."""
        if not self.connected:
            super().plug()
            self.bus_reset()

    # --- inspection ---

    @property
    def outputs(self) -> tuple[bool, ...]:
        """Whether each of the six outputs is on."""
        return tuple(self._outputs)

    @property
    def trips(self) -> tuple[bool, ...]:
        """Whether each output's over-current trip flag is set."""
        return tuple(self._trips)

    @property
    def run_led(self) -> bool:
        """Whether the RUN LED is lit."""
        return self._run_led

    @property
    def error_led(self) -> bool:
        """Whether the ERROR LED is lit."""
        return self._error_led

    @property
    def output_drivers_ready(self) -> bool:
        """Whether the output drivers started at boot (battery above 10.2 V then)."""
        return self._drivers_ready

    @property
    def note_queue(self) -> list[PiezoNote]:
        """The queued piezo notes still to finish now, the one playing first."""
        self._play_until_now()
        return list(self._notes)

    # --- time ---

    def use_clock(self, clock: Clock) -> None:
        """Play the piezo on ``clock`` from now on (a simulated kit gives its own)."""
        self._play_until_now()
        self._time.follow(clock)

    @property
    def clock(self) -> Clock:
        """The clock the firmware's piezo follows."""
        return self._time.clock

    # --- outside control ---

    def trip_output(self, output: int) -> None:
        """Simulate an over-current on ``output``: it switches off and stays off until reset."""
        self._check_output(output)
        self._trips[output] = True
        self._outputs[output] = False
        self._tell_listeners()

    def press_start(self, *, external: bool = False) -> None:
        """Hold the start button down (the internal one, or the external one)."""
        self._set_button(external=external, held=True)

    def release_start(self, *, external: bool = False) -> None:
        """Let go of the start button (the internal one, or the external one)."""
        self._set_button(external=external, held=False)

    def _set_button(self, *, external: bool, held: bool) -> None:
        if external:
            self._external_button = held
        else:
            self._internal_button = held
        self.ring_doorbells()  # a host waiting for a press reads the button now

    @property
    def start_button_pressed(self) -> bool:
        """Whether either start button is held now (what the button read reports)."""
        return self._internal_button or self._external_button

    @property
    def battery_voltage_mv(self) -> int:
        """The battery voltage in mV."""
        return self._battery_mv

    @property
    def battery_current_ma(self) -> int:
        """The true battery current in mA."""
        return self._battery_ma

    def set_output_current(self, output: int, amps: float) -> None:
        """Set the current that output ``output`` reports, in amps (stored in mA)."""
        self._check_output(output)
        if amps < 0:
            raise ValueError("output current cannot be negative")
        self._output_ma[output] = round(amps * 1000)

    def output_current(self, output: int) -> float:
        """The current output ``output`` reports, in amps (what it was set to, and the load)."""
        self._check_output(output)
        return self._reported_output_current(output) / 1000

    def _reported_output_current(self, output: int) -> int:
        return self._output_ma[output] + self._supplied_now_ma(output)

    def advance_piezo(self, milliseconds: int) -> list[PiezoNote]:
        """Let ``milliseconds`` pass beside the clock; return the notes that finished.

        That is every note finished since the queue was last looked at (by a request,
        :attr:`note_queue` or this), the clock's time included.

        :raises ValueError: ``milliseconds`` is negative (time only runs forwards).
        """
        if milliseconds < 0:
            raise ValueError("time only runs forwards")
        finished = self._play_until_now()
        self._time.skip(milliseconds / 1000)
        return finished + self._play_until_now()

    def _play_until_now(self) -> list[PiezoNote]:
        """Bring the piezo queue up to the board's time; return the notes that finished."""
        now = self._time.milliseconds()
        elapsed, self._piezo_ms = now - self._piezo_ms, now
        return self._play(elapsed)

    def _play(self, milliseconds: int) -> list[PiezoNote]:
        finished: list[PiezoNote] = []
        remaining = milliseconds
        while self._notes:
            head = self._notes[0]
            left_of_head = head.duration_ms - self._note_elapsed_ms
            if remaining < left_of_head:
                self._note_elapsed_ms += remaining
                break
            remaining -= left_of_head
            finished.append(self._notes.popleft())
            self._note_elapsed_ms = 0
        return finished

    def _stop_piezo(self) -> None:
        self._piezo_ms = self._time.milliseconds()
        self._notes.clear()
        self._note_elapsed_ms = 0

    # --- what the firmware reports ---

    def _reported_battery_current(self) -> int:
        """The fw 3 battery current: shunt steps of 20 mA; below the offset it reads 1 mA."""
        true_ma = self._battery_ma + round(self.load_current * 1000)
        sensed = (true_ma + _BATTERY_OFFSET_MA) // _SHUNT_STEP_MA * _SHUNT_STEP_MA
        if sensed < _BATTERY_OFFSET_MA:
            return 1
        return sensed - _BATTERY_OFFSET_MA

    def _reported_battery_voltage(self) -> int:
        """The INA219 bus voltage: 4 mV steps up to its 32 V range."""
        loaded_mv = round(self.loaded_voltage * 1000)
        return min(loaded_mv // _BUS_STEP_MV * _BUS_STEP_MV, _BUS_MAX_MV)

    # --- the firmware's request handlers ---

    def _read(self, command: int, length: int) -> bytes:
        if command <= _READ_OUTPUT_LAST:
            reply = _U32.pack(self._reported_output_current(command))
        elif command == _READ_5V_RAIL:
            reply = bytes(self._control_buffer[:4])
        elif command == _READ_BATTERY:
            reply = _BATTERY.pack(
                self._reported_battery_current(), self._reported_battery_voltage()
            )
        elif command == _READ_BUTTON:
            reply = _U32.pack(int(self.start_button_pressed))
        elif command == _READ_VERSION:
            reply = _U32.pack(self.version)
        else:
            raise UsbStall()
        if length < len(reply):
            raise UsbStall()
        return reply

    def _write(self, value: int, command: int, data: bytes) -> None:
        if command <= _WRITE_OUTPUT_LAST:
            self._switch_output(command, on=value != 0)
        elif command == _WRITE_RUN_LED:
            self._run_led = value != 0
        elif command == _WRITE_ERROR_LED:
            self._error_led = value != 0
        elif command == _WRITE_PIEZO:
            self._queue_notes(data)
        else:
            raise UsbStall()

    def _switch_output(self, output: int, *, on: bool) -> None:
        if not on:
            self._outputs[output] = False
        elif self._drivers_ready and not self._trips[output]:
            self._outputs[output] = True

    def _queue_notes(self, data: bytes) -> None:
        if not data or len(data) % _SAMPLE.size:
            raise UsbStall()
        self._play_until_now()  # the queue's room is what is left of it now
        notes = [PiezoNote(*sample) for sample in _SAMPLE.iter_unpack(data)]
        free_slots = _RING_SLOTS - len(self._notes)
        if len(notes) >= free_slots:
            raise UsbStall()
        self._notes.extend(notes)
