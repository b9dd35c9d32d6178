"""Finding boards: serial ports by USB identity, and USB devices by vendor and product.

:func:`list_serial_ports` turns pyserial's port list into typed :class:`PortInfo` records,
and :func:`match_ports` picks the ones a backend drives. :func:`find_usb_devices` wraps
pyusb's search with errors that say what to install. Both take an injectable source so
tests (and simulated environments) can offer ports and devices that do not exist.
"""

from __future__ import annotations

import logging
import os
import sys
from collections.abc import Callable, Iterable
from typing import Any, Protocol

from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import CommunicationError, USBCommunicationError

from .usb_link import USBDeviceLike

__all__ = [
    "FTDI_VENDOR_ID",
    "ComPortLike",
    "PortInfo",
    "USBFinder",
    "find_port",
    "find_usb_devices",
    "libusb_help",
    "list_serial_ports",
    "match_ports",
]

_log = logging.getLogger(__name__)

#: The USB vendor ID of FTDI, whose adapters (the SR motor board's) want low-latency mode.
FTDI_VENDOR_ID = 0x0403


class ComPortLike(Protocol):
    """The fields of pyserial's ``ListPortInfo`` that :class:`PortInfo` reads (read-only)."""

    @property
    def device(self) -> str:
        """The path or name to open."""

    @property
    def vid(self) -> int | None:
        """The USB vendor ID, if any."""

    @property
    def pid(self) -> int | None:
        """The USB product ID, if any."""

    @property
    def serial_number(self) -> str | None:
        """The USB serial number string, if any."""

    @property
    def manufacturer(self) -> str | None:
        """The USB manufacturer string, if any."""

    @property
    def product(self) -> str | None:
        """The USB product string, if any."""

    @property
    def description(self) -> str:
        """A human description from the operating system."""


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: every
# program imports it, and making the generated ones costs a third of a millisecond. A
# test checks them against those.)
@frozen_record
class PortInfo(FrozenRecord):
    """A serial port, and the USB identity of the device behind it if it has one."""

    #: The path or name to open, such as ``/dev/ttyACM0`` or ``COM3``.
    device: str
    #: The USB vendor ID, or ``None`` for a port that is not a USB device.
    vid: int | None = None
    #: The USB product ID, or ``None``.
    pid: int | None = None
    #: The USB serial number string, or ``None`` if the device reports none.
    serial_number: str | None = None
    #: The USB manufacturer string, or ``None``.
    manufacturer: str | None = None
    #: The USB product string, or ``None``.
    product: str | None = None
    #: A human description from the operating system.
    description: str = ""

    def __init__(
        self,
        device: str,
        vid: int | None = None,
        pid: int | None = None,
        serial_number: str | None = None,
        manufacturer: str | None = None,
        product: str | None = None,
        description: str = "",
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "device", device)
        set_field(self, "vid", vid)
        set_field(self, "pid", pid)
        set_field(self, "serial_number", serial_number)
        set_field(self, "manufacturer", manufacturer)
        set_field(self, "product", product)
        set_field(self, "description", description)

    @classmethod
    def from_comport(cls, port: ComPortLike) -> PortInfo:
        """Make a :class:`PortInfo` from a pyserial ``ListPortInfo`` (or alike)."""
        return cls(
            device=port.device,
            vid=port.vid,
            pid=port.pid,
            serial_number=port.serial_number,
            manufacturer=port.manufacturer,
            product=port.product,
            description=port.description or "",
        )

    @property
    def is_ftdi(self) -> bool:
        """Whether the device is an FTDI USB-serial adapter."""
        return self.vid == FTDI_VENDOR_ID


def _pyserial_comports() -> Iterable[ComPortLike]:
    from serial.tools import list_ports

    ports: Iterable[ComPortLike] = list_ports.comports()
    return ports


def list_serial_ports(source: Callable[[], Iterable[ComPortLike]] | None = None) -> list[PortInfo]:
    """List the serial ports of this machine.

    :param source: where to get the ports; defaults to pyserial's
        ``serial.tools.list_ports.comports``. Tests pass a function returning stand-ins.
    :raises CommunicationError: the operating system would not list its ports.
    """
    try:
        ports = list((source or _pyserial_comports)())
    except OSError as exc:
        raise CommunicationError(f"Could not list the serial ports of this machine: {exc}") from exc
    return [PortInfo.from_comport(port) for port in ports]


def match_ports(
    ports: Iterable[PortInfo],
    ids: set[tuple[int, int]],
    manufacturer: str | None = None,
    product: str | None = None,
) -> list[PortInfo]:
    """Return the ports whose USB (vendor, product) ID is in ``ids``, in a stable order.

    :param manufacturer: if given, the USB manufacturer string must be exactly this.
    :param product: if given, the USB product string must be exactly this.
    """
    found = [
        port
        for port in ports
        if port.vid is not None
        and port.pid is not None
        and (port.vid, port.pid) in ids
        and (manufacturer is None or port.manufacturer == manufacturer)
        and (product is None or port.product == product)
    ]
    return sorted(found, key=lambda port: (port.serial_number or "", port.device))


def find_port(
    device: str, source: Callable[[], Iterable[ComPortLike]] | None = None
) -> PortInfo | None:
    """Return the :class:`PortInfo` of the port at path ``device`` (symlinks resolved)."""
    wanted = os.path.realpath(device)
    for port in list_serial_ports(source):
        if os.path.realpath(port.device) == wanted:
            return port
    return None


class USBFinder(Protocol):
    """The shape of ``usb.core.find``, as :func:`find_usb_devices` calls it."""

    def __call__(self, *, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
        """Return an iterable of the matching devices."""
        ...


_LIBUSB_HELP = (
    "pyusb found no libusb backend, so USB boards cannot be used. Install libusb: "
    "on Debian or Ubuntu `sudo apt install libusb-1.0-0`, on macOS `brew install libusb`, "
    "on Windows put libusb-1.0.dll (from https://libusb.info) beside python.exe or "
    "`pip install libusb-package`."
)

_LIBUSB_UNUSABLE_HELP = (
    "libusb is installed ({library}), but pyusb could not use it, so USB boards cannot be "
    "used. It may be built for another architecture than this Python, or too old: "
    "`pip install libusb-package` brings one that fits, and running with "
    "PYUSB_DEBUG=debug shows why pyusb refused it."
)


def libusb_help(find_library: Callable[[str], str | None] | None = None) -> str:
    """What to do when pyusb has no backend: install libusb, or fix the one installed.

    :param find_library: looks a shared library up by name (``ctypes.util.find_library``).
    """
    if find_library is None:
        import ctypes.util

        find_library = ctypes.util.find_library
    for name in ("usb-1.0", "libusb-1.0"):
        library = find_library(name)
        if library:
            return _LIBUSB_UNUSABLE_HELP.format(library=library)
    return _LIBUSB_HELP


def _pyusb_find(*, find_all: bool, idVendor: int, idProduct: int) -> Any:  # noqa: N803
    import usb.core

    return usb.core.find(find_all=find_all, idVendor=idVendor, idProduct=idProduct)


def find_usb_devices(vid: int, pid: int, *, finder: USBFinder | None = None) -> list[USBDeviceLike]:
    """Return every connected USB device with vendor ID ``vid`` and product ID ``pid``.

    Blocks briefly while the bus is scanned; from async code call it through
    ``anyio.to_thread.run_sync``.

    :param finder: the search to run, shaped like ``usb.core.find``; defaults to it.
    :raises CommunicationError: no libusb backend is installed (the message says how
        to install one).
    :raises USBCommunicationError: the bus could not be scanned.
    """
    search = finder or _pyusb_find
    try:
        devices: Iterable[USBDeviceLike] = search(find_all=True, idVendor=vid, idProduct=pid)
        return list(devices)
    except Exception as exc:
        # pyusb is looked up, not imported: a search that raised one of its errors has
        # loaded it (a simulated kit's search never does).
        core = sys.modules.get("usb.core")
        if core is not None and isinstance(exc, core.NoBackendError):
            raise CommunicationError(libusb_help()) from exc
        if core is not None and isinstance(exc, core.USBError):
            raise USBCommunicationError(
                f"Could not scan the USB bus for devices {vid:04x}:{pid:04x}: {exc}", exc
            ) from exc
        raise
