"""Simulator of the SR Servo Board v4 running firmware 2 (USB control transfers).

Protocol (:doc:`/internals/sr-servo-board`), ``bRequest`` 64, standard type, device recipient:

- read wIndex 9, wLength >= 4: the firmware version, ``uint32`` 2. Any other read stalls.
- write wIndex 0-11: servo n's position, wValue as a signed 16-bit number (0xFF9C is -100),
  clamped to -100..100. The pulse is ``1500 + 5 * position`` µs.
- write wIndex 12: initialise (configure the I²C expander, start pulses). Until then no
  servo pulses at all.
- write wIndex 13 or more stalls.

The expander is powered from the board's 12 V input. Without it (``has_12v=False``) the
initialise request hangs in the firmware's I²C set-up: the host sees a timeout (errno 110)
and every later transfer times out too, until 12 V comes back and the set-up completes.
Servos get no pulses while the 12 V is off. A kit's wiring switches the 12 V through
:attr:`~SRServoBoardFw2Simulator.powered` (the same as ``has_12v``).
"""

from __future__ import annotations

import struct
from typing import ClassVar, Final

from .loads import SERVO_BOARD_IDLE_CURRENT, SERVO_HOLDING_CURRENT
from .sr_usb import SRUsbBoardSimulator
from .usb_support import UsbStall, timeout_error

__all__ = ["SRServoBoardFw2Simulator"]

_U32: Final = struct.Struct("<I")
_READ_VERSION: Final = 9
_WRITE_INITIALISE: Final = 12
_POSITION_LIMIT: Final = 100
_CENTRE_US: Final = 1500
_US_PER_STEP: Final = 5


def _signed16(value: int) -> int:
    return value - 0x10000 if value & 0x8000 else value


class SRServoBoardFw2Simulator(SRUsbBoardSimulator):
    """An SR Servo Board v4 with firmware 2, seen through pyusb."""

    idVendor: ClassVar[int] = 0x1BDA  # noqa: N815
    idProduct: ClassVar[int] = 0x0011  # noqa: N815
    bcdDevice: ClassVar[int] = 0x0402  # noqa: N815
    #: The firmware version this board reports.
    version: ClassVar[int] = 2
    #: Number of servo channels.
    SERVO_COUNT: ClassVar[int] = 12

    def __init__(self, serial_number: str | None, *, has_12v: bool = True) -> None:
        super().__init__(serial_number, manufacturer="Student Robotics", product="Servo Board v4")
        self._has_12v = has_12v
        self._positions = [0] * self.SERVO_COUNT
        self._initialised = False
        self._hung = False
        self._init_requests = 0

    # --- inspection ---

    @property
    def initialised(self) -> bool:
        """Whether the initialise request has completed (servo pulses are running)."""
        return self._initialised

    @property
    def init_requests(self) -> int:
        """How many initialise requests the board has received since power-up."""
        return self._init_requests

    @property
    def hung(self) -> bool:
        """Whether the firmware is stuck in the I²C set-up, waiting for 12 V."""
        return self._hung

    @property
    def positions(self) -> tuple[int, ...]:
        """The stored position of each servo, -100..100."""
        return tuple(self._positions)

    @property
    def pulse_widths_us(self) -> tuple[int | None, ...]:
        """Each servo's pulse width in µs, or None while the board is not initialised.

        Without 12 V the expander that makes the pulses is off: every one is None.
        """
        if not self._initialised or not self._has_12v:
            return (None,) * self.SERVO_COUNT
        return tuple(_CENTRE_US + _US_PER_STEP * position for position in self._positions)

    # --- outside control ---

    @property
    def has_12v(self) -> bool:
        """Whether the board's 12 V input is powered."""
        return self._has_12v

    @has_12v.setter
    def has_12v(self, powered: bool) -> None:
        self._has_12v = powered
        if powered and self._hung:
            self._hung = False
            self._initialised = True

    @property
    def powered(self) -> bool:
        """Whether the board's 12 V input is on: :attr:`has_12v` under a kit wiring's name."""
        return self._has_12v

    @powered.setter
    def powered(self, on: bool) -> None:
        self.has_12v = on

    def supply_current(self) -> float:
        """The amps the board draws from its 12 V input now (see :mod:`.loads`)."""
        if not self._has_12v:
            return 0.0
        # (every servo is pulsed once the board is initialised: see pulse_widths_us)
        pulsing = self.SERVO_COUNT if self._initialised else 0
        return SERVO_BOARD_IDLE_CURRENT + pulsing * SERVO_HOLDING_CURRENT

    def power_cycle(self) -> None:
        """Switch the board off and on: positions back to 0, not initialised, not hung."""
        self._control_buffer[:] = bytes(len(self._control_buffer))
        self._positions = [0] * self.SERVO_COUNT
        self._initialised = False
        self._hung = False
        self._init_requests = 0

    # --- the firmware's request handlers ---

    def _control_in(
        self, request_type: int, request: int, value: int, index: int, length: int
    ) -> bytes:
        if self._hung:
            raise timeout_error()
        return super()._control_in(request_type, request, value, index, length)

    def _control_out(
        self, request_type: int, request: int, value: int, index: int, data: bytes
    ) -> None:
        if self._hung:
            raise timeout_error()
        super()._control_out(request_type, request, value, index, data)

    def _read(self, command: int, length: int) -> bytes:
        if command != _READ_VERSION or length < _U32.size:
            raise UsbStall()
        return _U32.pack(self.version)

    def _write(self, value: int, command: int, data: bytes) -> None:
        if command < self.SERVO_COUNT:
            position = _signed16(value)
            self._positions[command] = max(-_POSITION_LIMIT, min(_POSITION_LIMIT, position))
        elif command == _WRITE_INITIALISE:
            self._init_requests += 1
            if not self._has_12v:
                self._hung = True
                raise timeout_error()
            self._initialised = True
        else:
            raise UsbStall()
