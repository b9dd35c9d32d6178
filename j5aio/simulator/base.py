"""The two seams every board simulator plugs into: a serial port and a USB device.

A simulator is a synchronous state machine: it never sleeps, never starts a thread and
never reads the computer's clock. A firmware that keeps time reads it from the clock it is
given (:mod:`j5aio.simulator.clock`), when its state is read or bytes arrive. Transports
(in-memory serial links, a fake pyusb device, a pty) wrap it and add the wire's timing.

- :class:`SerialBoardSimulator` is a board behind a UART: the host opens the port, writes
  bytes and reads what the board emits.
- :class:`UsbBoardSimulator` quacks like the part of a pyusb ``usb.core.Device`` that a
  control-transfer backend uses.
"""

from __future__ import annotations

import array
import contextlib
import errno
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator
from typing import ClassVar

from .usb_support import (
    DFU_RUNTIME_INTERFACE,
    ControlData,
    SimulatedConfiguration,
    SimulatedInterface,
    UsbStall,
    as_payload,
    no_device_error,
    pipe_error,
)

__all__ = ["PluggedBoard", "SerialBoardSimulator", "SimulatorUnpluggedError", "UsbBoardSimulator"]


class SimulatorUnpluggedError(OSError):
    """The host talked to a simulated serial board while it was unplugged.

    Transports are expected to check :attr:`PluggedBoard.connected` and raise their
    own disconnection error first; this is the simulator's safety net.
    """

    def __init__(self) -> None:
        super().__init__(errno.ENODEV, "the simulated board is unplugged")


class PluggedBoard:
    """What every simulated board has: a USB cable to pull out, and listeners to tell.

    :class:`SerialBoardSimulator` and :class:`UsbBoardSimulator` build on it.
    """

    def __init__(self) -> None:
        self._connected = True
        self._connection = 0
        self._listeners: list[Callable[[], None]] = []

    def listen(self, listener: Callable[[], None]) -> Callable[[], None]:
        """Call ``listener`` each time the board may have changed state.

        That is after the board took what the host sent (bytes, or a host-to-device
        transfer), after it rebooted, and whenever the simulator says so, in the thread
        that did it. Returns the function that stops the calls.
        """
        self._listeners.append(listener)

        def stop() -> None:
            with contextlib.suppress(ValueError):
                self._listeners.remove(listener)

        return stop

    def _tell_listeners(self) -> None:
        for listener in tuple(self._listeners):
            listener()

    @property
    def connected(self) -> bool:
        """Whether the board is plugged in."""
        return self._connected

    @property
    def connection(self) -> int:
        """A number that changes each time the board is unplugged.

        A port or device opened before an unplug is dead for good, as a real one is after
        its cable came out: transports compare this number with the one they saw at
        opening.
        """
        return self._connection

    def unplug(self) -> None:
        """Pull the USB cable out: the host's exchanges with the board now fail."""
        if self._connected:
            self._connection += 1
        self._connected = False


class SerialBoardSimulator(PluggedBoard, ABC):
    """A board that talks to the host over a serial port.

    Subclasses set the class attributes describing the real board and implement
    :meth:`_boot` and :meth:`_process`. Data may arrive split at any byte boundary:
    :meth:`_process` must keep its parser state between calls.
    """

    #: The UART speed the real board uses.
    baudrate: ClassVar[int]
    #: Seconds the real board needs after the port opens before it listens.
    boot_delay: ClassVar[float]
    #: Whether opening the port reboots the board (DTR wired to reset, as on an Arduino).
    resets_on_open: ClassVar[bool]
    #: Whether the board is powered by its USB cable, so that plugging it in boots it.
    powered_by_usb: ClassVar[bool]

    def __init__(
        self,
        serial_number: str,
        *,
        usb_vid: int,
        usb_pid: int,
        manufacturer: str | None,
        product: str | None,
    ) -> None:
        #: The USB serial number of the board's USB-serial adapter.
        self.serial_number = serial_number
        #: The USB vendor id that port discovery shows.
        self.usb_vid = usb_vid
        #: The USB product id that port discovery shows.
        self.usb_pid = usb_pid
        #: The USB manufacturer string that port discovery shows.
        self.manufacturer = manufacturer
        #: The USB product string that port discovery shows.
        self.product = product
        super().__init__()

    def open(self) -> bytes:
        """Tell the board the host opened its port; return what the board prints at boot.

        Boards that reset on open reboot here; the others print nothing and keep their state.
        """
        self._require_connected()
        if self.resets_on_open:
            return self._boot()
        return b""

    def receive(self, data: bytes) -> bytes:
        """Feed bytes the host wrote; return every byte the board emits in response."""
        self._require_connected()
        emitted = self._process(bytes(data))
        if self._listeners:
            self._tell_listeners()
        return emitted

    def reset(self) -> bytes:
        """Reboot the board (reset button or power cycle); return what it prints at boot."""
        booted = self._boot()
        if self._listeners:
            self._tell_listeners()
        return booted

    def plug(self) -> None:
        """Plug the USB cable back in; a USB-powered board boots (with nobody listening)."""
        if not self._connected and self.powered_by_usb:
            self._boot()
        self._connected = True

    def _require_connected(self) -> None:
        if not self._connected:
            raise SimulatorUnpluggedError()

    @abstractmethod
    def _boot(self) -> bytes:
        """Put the firmware in its power-on state; return what it prints at boot."""

    @abstractmethod
    def _process(self, data: bytes) -> bytes:
        """Run the firmware on received bytes; return what it emits."""


class UsbBoardSimulator(PluggedBoard, ABC):
    """A board driven by USB control transfers, shaped like a pyusb ``usb.core.Device``.

    Subclasses set the descriptor class attributes and implement :meth:`_control_in` and
    :meth:`_control_out`, raising :class:`~j5aio.simulator.usb_support.UsbStall` to stall.
    """

    idVendor: ClassVar[int]  # noqa: N815 - pyusb's attribute names
    idProduct: ClassVar[int]  # noqa: N815
    bcdDevice: ClassVar[int]  # noqa: N815
    #: The USB interfaces of the (single) configuration.
    interface_descriptors: ClassVar[tuple[SimulatedInterface, ...]] = (DFU_RUNTIME_INTERFACE,)
    bNumConfigurations: ClassVar[int] = 1  # noqa: N815

    def __init__(
        self, serial_number: str | None, *, manufacturer: str | None, product: str | None
    ) -> None:
        self._serial_number = serial_number
        self._manufacturer = manufacturer
        self._product = product
        self._strings_read: set[str] = set()
        self._configuration = SimulatedConfiguration(1, self.interface_descriptors)
        super().__init__()

    # --- descriptor strings: read from the device once, then cached, as pyusb does ---

    def _string(self, name: str, value: str | None) -> str | None:
        if name not in self._strings_read:
            if not self._connected:
                raise no_device_error()
            self._strings_read.add(name)
        return value

    @property
    def serial_number(self) -> str | None:
        """The USB serial number string (None when the device has none)."""
        return self._string("serial_number", self._serial_number)

    @property
    def manufacturer(self) -> str | None:
        """The USB manufacturer string."""
        return self._string("manufacturer", self._manufacturer)

    @property
    def product(self) -> str | None:
        """The USB product string."""
        return self._string("product", self._product)

    # --- configurations ---

    def get_active_configuration(self) -> SimulatedConfiguration:
        """Return the active configuration (there is only one)."""
        self._require_connected()
        return self._configuration

    def set_configuration(self, configuration: int | None = None) -> None:
        """Select the configuration; the boards have exactly one, so this only checks presence."""
        self._require_connected()

    def configurations(self) -> tuple[SimulatedConfiguration, ...]:
        """Return every configuration, as ``Device.configurations()`` does."""
        return (self._configuration,)

    def __iter__(self) -> Iterator[SimulatedConfiguration]:
        """Iterate over the configurations, as iterating a pyusb device does."""
        return iter(self.configurations())

    def __getitem__(self, index: int) -> SimulatedConfiguration:
        """Return configuration number ``index`` (only 0 exists)."""
        return self.configurations()[index]

    # --- plugging ---

    def plug(self) -> None:
        """Plug the USB cable back in."""
        self._connected = True

    def _require_connected(self) -> None:
        if not self._connected:
            raise no_device_error()

    # --- control transfers ---

    def ctrl_transfer(
        self,
        bmRequestType: int,  # noqa: N803 - pyusb's parameter names
        bRequest: int,  # noqa: N803
        wValue: int = 0,  # noqa: N803
        wIndex: int = 0,  # noqa: N803
        data_or_wLength: ControlData = None,  # noqa: N803
        timeout: int | None = None,
    ) -> array.array[int] | int:
        """Do a control transfer on endpoint 0, as ``usb.core.Device.ctrl_transfer`` does.

        IN transfers return an ``array('B')`` of the bytes read (or, when given an array to
        fill, the number of bytes read); OUT transfers return the number of bytes written.
        A stalled request raises ``usb.core.USBError`` with errno 32 (EPIPE); an unplugged
        device raises one with errno 19 (ENODEV). ``timeout`` is accepted and ignored: a
        simulator answers at once.
        """
        self._require_connected()
        # Like pyusb's ctypes call, the setup fields are silently truncated to their widths.
        request_type = bmRequestType & 0xFF
        request = bRequest & 0xFF
        value = wValue & 0xFFFF
        index = wIndex & 0xFFFF
        if request_type & 0x80:
            target: array.array[int] | None = None
            if isinstance(data_or_wLength, array.array):
                target = data_or_wLength
                length = len(target) * target.itemsize
            elif data_or_wLength is None:
                length = 0
            elif isinstance(data_or_wLength, int):
                length = data_or_wLength
            else:
                length = len(as_payload(data_or_wLength))
            try:
                reply = self._control_in(request_type, request, value, index, length & 0xFFFF)
            except UsbStall:
                raise pipe_error() from None
            reply = reply[:length]
            if target is not None:
                for position, byte in enumerate(reply):
                    target[position] = byte
                return len(reply)
            return array.array("B", reply)
        payload = as_payload(data_or_wLength)
        try:
            self._control_out(request_type, request, value, index, payload)
        except UsbStall:
            raise pipe_error() from None
        finally:
            if self._listeners:
                self._tell_listeners()
        return len(payload)

    @abstractmethod
    def _control_in(
        self, request_type: int, request: int, value: int, index: int, length: int
    ) -> bytes:
        """Answer a device-to-host request; raise :class:`.UsbStall` to stall."""

    @abstractmethod
    def _control_out(
        self, request_type: int, request: int, value: int, index: int, data: bytes
    ) -> None:
        """Handle a host-to-device request; raise :class:`.UsbStall` to stall."""
