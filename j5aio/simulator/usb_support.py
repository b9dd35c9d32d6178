"""Pieces that let a simulator look like a pyusb ``usb.core.Device`` to a backend.

This module holds the exact errors pyusb's libusb1 backend raises, the tiny stand-ins for a
device's configuration and interfaces, and the conversion of a ``data_or_wLength`` argument
the way pyusb does it.
"""

from __future__ import annotations

import array
import errno
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, TypeAlias

from j5aio._records import FrozenRecord, frozen_record

if TYPE_CHECKING:  # (pyusb is imported when an error is made: a kit's start makes none)
    import usb.core

__all__ = [
    "CONTROL_BUFFER_SIZE",
    "ControlData",
    "SimulatedConfiguration",
    "SimulatedInterface",
    "UsbStall",
    "as_payload",
    "no_device_error",
    "pipe_error",
    "timeout_error",
]

#: What ``ctrl_transfer`` accepts as its ``data_or_wLength`` argument, as pyusb does.
ControlData: TypeAlias = "int | bytes | bytearray | array.array[int] | Iterable[int] | str | None"

#: The size of the control-transfer buffer of the SR STM32 firmwares (libopencm3 ``usbd_init``).
CONTROL_BUFFER_SIZE = 128

# libusb error codes, as the libusb1 backend of pyusb reports them in ``backend_error_code``.
_LIBUSB_ERROR_NO_DEVICE = -4
_LIBUSB_ERROR_TIMEOUT = -7
_LIBUSB_ERROR_PIPE = -9


def pipe_error() -> usb.core.USBError:
    """Return the error pyusb raises when the device stalls a control request."""
    import usb.core

    return usb.core.USBError("Pipe error", _LIBUSB_ERROR_PIPE, errno.EPIPE)


def no_device_error() -> usb.core.USBError:
    """Return the error pyusb raises when the device has gone away."""
    import usb.core

    return usb.core.USBError(
        "No such device (it may have been disconnected)", _LIBUSB_ERROR_NO_DEVICE, errno.ENODEV
    )


def timeout_error() -> usb.core.USBTimeoutError:
    """Return the error pyusb raises when a control transfer is not completed in time."""
    import usb.core

    return usb.core.USBTimeoutError("Operation timed out", _LIBUSB_ERROR_TIMEOUT, errno.ETIMEDOUT)


class UsbStall(Exception):  # noqa: N818 - a USB stall is the name of the event, not an error
    """Raised inside a simulator's request handler to stall the control request."""


def as_payload(data_or_wlength: ControlData) -> bytes:
    """Convert an OUT transfer's ``data_or_wLength`` to the bytes pyusb would send.

    As in pyusb: ``None`` is no data, an int is that many zero bytes, a string is sent as
    UTF-8, anything else must be an iterable of byte values.
    """
    if data_or_wlength is None:
        return b""
    if isinstance(data_or_wlength, int):
        return bytes(data_or_wlength)
    if isinstance(data_or_wlength, str):
        return data_or_wlength.encode("utf-8")
    return bytes(data_or_wlength)


# The two dataclasses below write their own ``__init__`` and take freezing, ``__repr__``,
# ``__eq__`` and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make
# them: every simulated kit with a USB board imports them, and making the generated ones
# costs a quarter of a millisecond a class. A test checks them against the generated ones.


@frozen_record
class SimulatedInterface(FrozenRecord):
    """The subset of a pyusb ``Interface`` that discovery code looks at."""

    bInterfaceNumber: int  # noqa: N815 - pyusb's attribute names
    bAlternateSetting: int  # noqa: N815
    bInterfaceClass: int  # noqa: N815
    bInterfaceSubClass: int  # noqa: N815
    bInterfaceProtocol: int  # noqa: N815
    bNumEndpoints: int = 0  # noqa: N815

    def __init__(
        self,
        bInterfaceNumber: int,  # noqa: N803 - pyusb's attribute names
        bAlternateSetting: int,  # noqa: N803
        bInterfaceClass: int,  # noqa: N803
        bInterfaceSubClass: int,  # noqa: N803
        bInterfaceProtocol: int,  # noqa: N803
        bNumEndpoints: int = 0,  # noqa: N803
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "bInterfaceNumber", bInterfaceNumber)
        set_field(self, "bAlternateSetting", bAlternateSetting)
        set_field(self, "bInterfaceClass", bInterfaceClass)
        set_field(self, "bInterfaceSubClass", bInterfaceSubClass)
        set_field(self, "bInterfaceProtocol", bInterfaceProtocol)
        set_field(self, "bNumEndpoints", bNumEndpoints)


#: The DFU-runtime interface that the SR STM32 boards expose (class 0xFE, subclass 1, protocol 1).
DFU_RUNTIME_INTERFACE = SimulatedInterface(
    bInterfaceNumber=0,
    bAlternateSetting=0,
    bInterfaceClass=0xFE,
    bInterfaceSubClass=0x01,
    bInterfaceProtocol=0x01,
)


@frozen_record
class SimulatedConfiguration(FrozenRecord):
    """The subset of a pyusb ``Configuration``: its value and its interfaces."""

    bConfigurationValue: int  # noqa: N815 - pyusb's attribute names
    interface_list: tuple[SimulatedInterface, ...]

    def __init__(
        self,
        bConfigurationValue: int,  # noqa: N803 - pyusb's attribute name
        interface_list: tuple[SimulatedInterface, ...],
    ) -> None:
        object.__setattr__(self, "bConfigurationValue", bConfigurationValue)
        object.__setattr__(self, "interface_list", interface_list)

    @property
    def bNumInterfaces(self) -> int:  # noqa: N802 - pyusb's attribute name
        """How many interfaces this configuration has."""
        return len(self.interface_list)

    def interfaces(self) -> tuple[SimulatedInterface, ...]:
        """Return the interfaces, as ``Configuration.interfaces()`` does."""
        return self.interface_list

    def __iter__(self) -> Iterator[SimulatedInterface]:
        """Iterate over the interfaces, as iterating a pyusb configuration does."""
        return iter(self.interface_list)

    def __getitem__(self, index: tuple[int, int]) -> SimulatedInterface:
        """Return the interface at ``(interface number, alternate setting)``."""
        number, alternate = index
        for interface in self.interface_list:
            if (interface.bInterfaceNumber, interface.bAlternateSetting) == (number, alternate):
                return interface
        raise IndexError(f"no interface {index!r}")
