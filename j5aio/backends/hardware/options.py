"""How hardware discovery finds ports and devices: real ones, or stand-ins for tests."""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Iterable

from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.hardware.transports.discovery import ComPortLike, USBFinder
from j5aio.backends.hardware.transports.stream import ByteStream

__all__ = ["DiscoveryOptions", "StreamOpener"]

StreamOpener = Callable[[str, int], Awaitable[ByteStream]]
"""Opens a port (path or URL) at a baud rate;
:func:`~j5aio.backends.hardware.transports.serial_stream.open_serial_stream` by default."""


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: every
# program imports it, and making the generated ones costs a third of a millisecond. A
# test checks them against those.)
@frozen_record
class DiscoveryOptions(FrozenRecord):
    """Where discovery looks for boards, and how patiently it waits for them.

    Every field has the real thing as its default, so ``DiscoveryOptions()`` is what
    ``discover()`` uses on a robot.
    """

    #: Lists the serial ports; pyserial's ``comports`` when ``None``.
    port_source: Callable[[], Iterable[ComPortLike]] | None = None
    #: Finds USB devices by vendor and product; pyusb's ``usb.core.find`` when ``None``.
    usb_finder: USBFinder | None = None
    #: Opens a serial port; ``open_serial_stream`` when ``None``.
    opener: StreamOpener | None = None
    #: Multiplies the waits for a board to boot (1 on real hardware; less for a
    #: simulated board that boots faster).
    time_scale: float = 1.0
    #: Log a board that fails its handshake and carry on, rather than raise.
    skip_failures: bool = False
    #: Tell apart the kinds of board that share a port's USB IDs (the Arduinos) by
    #: identifying each such port once (see :mod:`j5aio.backends.hardware.identify`),
    #: rather than trying every matching port as the kind asked for. Off where the ports
    #: listed are known to be of the kind asked for (a simulated kit's).
    identify_shared_ports: bool = True

    def __init__(
        self,
        port_source: Callable[[], Iterable[ComPortLike]] | None = None,
        usb_finder: USBFinder | None = None,
        opener: StreamOpener | None = None,
        time_scale: float = 1.0,
        skip_failures: bool = False,
        identify_shared_ports: bool = True,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "port_source", port_source)
        set_field(self, "usb_finder", usb_finder)
        set_field(self, "opener", opener)
        set_field(self, "time_scale", time_scale)
        set_field(self, "skip_failures", skip_failures)
        set_field(self, "identify_shared_ports", identify_shared_ports)
        self.__post_init__()

    def __post_init__(self) -> None:
        if not self.time_scale >= 0:
            raise ValueError(f"time_scale must be a number >= 0, not {self.time_scale!r}")
