"""The control-request convention shared by the SR v4 USB firmwares (power fw 3, servo fw 2).

Both firmwares (libopencm3 on an STM32F1) register one handler for *standard* requests to
the *device* recipient and answer only ``bRequest == 64``; the command is in ``wIndex``, a
parameter in ``wValue``, and bit 7 of ``bmRequestType`` gives the direction. Anything else
is stalled. Data stages go through one 128-byte control buffer, which keeps what the last
transfer left in it.

A host's poll may be told when to read: :meth:`SRUsbBoardSimulator.add_doorbell` (the
:class:`~j5aio.backends.hardware.transports.usb_link.RingingDevice` of the USB link) rings
whenever a board changes what a poll waits for (:meth:`SRUsbBoardSimulator.ring_doorbells`:
the power board's start buttons) and when its cable is pulled, so that the poll reads
at once, through the protocol, rather than at its next interval. Its transfers never block,
and it says so (``answers_at_once``): the link runs them without a thread of its own.
"""

from __future__ import annotations

import contextlib
from abc import abstractmethod
from collections.abc import Callable
from typing import ClassVar

from .base import UsbBoardSimulator
from .usb_support import CONTROL_BUFFER_SIZE, UsbStall

__all__ = ["SR_REQUEST", "SRUsbBoardSimulator"]

#: The only bRequest the SR firmwares answer.
SR_REQUEST = 64

_TYPE_AND_RECIPIENT_MASK = 0x7F


class SRUsbBoardSimulator(UsbBoardSimulator):
    """A board speaking the SR "request 64" control-transfer convention."""

    #: Its transfers are function calls that never block: a host's USB link runs them in
    #: its event loop, with no worker thread until it polls (see
    #: :func:`~j5aio.backends.hardware.transports.usb_link.answers_at_once`).
    answers_at_once: ClassVar[bool] = True

    def __init__(
        self, serial_number: str | None, *, manufacturer: str | None, product: str | None
    ) -> None:
        super().__init__(serial_number, manufacturer=manufacturer, product=product)
        self._control_buffer = bytearray(CONTROL_BUFFER_SIZE)
        self._doorbells: list[Callable[[], None]] = []

    def add_doorbell(self, ring: Callable[[], None]) -> Callable[[], None]:
        """Call ``ring()`` whenever a host's poll should read again; return what stops it.

        It rings (in the thread that made the change) when the board changes something a
        host polls for (see :meth:`ring_doorbells`) and when the board is unplugged.
        """
        self._doorbells.append(ring)

        def stop() -> None:
            with contextlib.suppress(ValueError):
                self._doorbells.remove(ring)

        return stop

    def ring_doorbells(self) -> None:
        """Tell every host polling the board that what it polls for may have changed."""
        for ring in tuple(self._doorbells):
            ring()

    def unplug(self) -> None:
        """Pull the USB cable out: every transfer now fails; a polling host reads at once."""
        super().unplug()
        self.ring_doorbells()

    @staticmethod
    def _check_request(request_type: int, request: int) -> None:
        if request != SR_REQUEST or request_type & _TYPE_AND_RECIPIENT_MASK:
            raise UsbStall()

    def _control_in(
        self, request_type: int, request: int, value: int, index: int, length: int
    ) -> bytes:
        self._check_request(request_type, request)
        reply = self._read(index, length)
        self._control_buffer[: len(reply)] = reply
        return reply

    def _control_out(
        self, request_type: int, request: int, value: int, index: int, data: bytes
    ) -> None:
        self._check_request(request_type, request)
        if len(data) > CONTROL_BUFFER_SIZE:
            raise UsbStall()
        self._control_buffer[: len(data)] = data
        self._write(value, index, data)

    @abstractmethod
    def _read(self, command: int, length: int) -> bytes:
        """Answer read command ``command`` (wIndex) with room for ``length`` bytes."""

    @abstractmethod
    def _write(self, value: int, command: int, data: bytes) -> None:
        """Carry out write command ``command`` (wIndex) with parameter ``value`` (wValue)."""
