"""Discovery of the simulated kit's boards, as the hardware backends' discovery sees them.

:func:`kit_discovery_options` gives the
:class:`~j5aio.backends.hardware.options.DiscoveryOptions` under which a hardware
backend finds the boards of a :class:`~j5aio.simulator.kit.SimulatedKit`: a serial board
as a port named ``sim://<kit name>/<serial number>``, a USB board as a
:class:`SimulatedUSBDevice`. The simulated environment
(:mod:`j5aio.simulator.environment`) is made of backends using them.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.transports._at_once import mark_answers_at_once
from j5aio.backends.hardware.transports.discovery import PortInfo
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.board_kinds import BoardKind, board_kinds

from .base import SerialBoardSimulator, UsbBoardSimulator
from .kit import SimulatedKit, current_kit
from .usb_support import no_device_error

if TYPE_CHECKING:
    from j5aio.backends.hardware.transports.stream import ByteStream

__all__ = [
    "MINIMUM_TIMEOUT_SCALE",
    "KitDiscovery",
    "SimulatedUSBDevice",
    "UnmatchedSimulatorWarning",
    "kind_options",
    "kit_discovery_options",
    "port_name",
]


def port_name(kit: SimulatedKit, simulator: SerialBoardSimulator) -> str:
    """Return the name a serial simulator's port has in ``kit``."""
    return f"sim://{kit.name}/{simulator.serial_number}"


class SimulatedUSBDevice:
    """A USB board simulator as discovery finds it, standing in for a pyusb device.

    Every attribute is the simulator's, with one addition: ``bus`` and ``address`` name
    its place in the kit (so that finding it again gives back the same board). Transfers
    go straight to the simulator, whose firmware keeps its own time
    (:mod:`j5aio.simulator.clock`).

    :param simulator: the simulated board.
    :param kit: the kit it belongs to.
    """

    def __init__(self, simulator: UsbBoardSimulator, kit: SimulatedKit) -> None:
        self._simulator = simulator
        #: The kit's name, in place of a USB bus number.
        self.bus = kit.name
        #: The board's serial number, in place of a USB address.
        self.address = simulator.serial_number
        self._connection = simulator.connection

    @property
    def simulator(self) -> UsbBoardSimulator:
        """The simulated board."""
        return self._simulator

    @property
    def idVendor(self) -> int:  # noqa: N802 - pyusb's name
        """The USB vendor ID."""
        return self._simulator.idVendor

    @property
    def idProduct(self) -> int:  # noqa: N802 - pyusb's name
        """The USB product ID."""
        return self._simulator.idProduct

    @property
    def serial_number(self) -> str | None:
        """The USB serial number string."""
        return self._simulator.serial_number

    def ctrl_transfer(
        self,
        bmRequestType: int,  # noqa: N803 - pyusb's names
        bRequest: int,  # noqa: N803
        wValue: int = 0,  # noqa: N803
        wIndex: int = 0,  # noqa: N803
        data_or_wLength: Any = None,  # noqa: N803
        timeout: int | None = None,
    ) -> Any:
        """Do a control transfer on the simulator, as pyusb does on a device.

        A device found before the board was unplugged is dead for good (errno 19), as a
        pyusb device is after its cable came out, even once the board is back.
        """
        if self._simulator.connection != self._connection:
            raise no_device_error()
        return self._simulator.ctrl_transfer(
            bmRequestType, bRequest, wValue, wIndex, data_or_wLength, timeout
        )

    def __getattr__(self, name: str) -> Any:
        return getattr(self._simulator, name)

    def __repr__(self) -> str:
        return f"<SimulatedUSBDevice {type(self._simulator).__name__} {self.address}>"


#: The least factor applied to the backends' timeouts on the simulated kit. A simulated
#: board answers at once, so a timeout costs nothing unless something is wrong; but a
#: timeout scaled to almost nothing (with a kit ``time_scale`` of 0) would fail whenever
#: the computer is busy.
MINIMUM_TIMEOUT_SCALE = 0.1


def kit_discovery_options(
    kit: SimulatedKit,
    serial_type: type[SerialBoardSimulator] = SerialBoardSimulator,
    *,
    timeout_scale: float | None = None,
    kind: BoardKind | None = None,
) -> DiscoveryOptions:
    """Return discovery options that find the plugged-in boards of ``kit``.

    Each serial board of ``serial_type`` (every serial board by default) is listed as a
    :class:`~j5aio.backends.hardware.transports.discovery.PortInfo`, and opening it gives a
    :class:`~j5aio.backends.hardware.transports.memory.SimulatorStream` to its simulator, with the
    kit's time scale. Each USB board is found as a :class:`SimulatedUSBDevice` by its vendor and
    product IDs. Any hardware discovery,
    :func:`~j5aio.backends.hardware.listing.find_boards` included, then finds the kit.

    :param kit: the kit whose boards to find.
    :param serial_type: list only the serial boards of this simulator class (the
        SourceBots Arduino and the Ruggeduino share their USB IDs, so each simulated
        backend looks at its own kind only).
    :param timeout_scale: the factor for the backends' timeouts (waiting for a board to
        boot, say); by default the kit's time scale, but at least
        :data:`~j5aio.simulator.discovery.MINIMUM_TIMEOUT_SCALE`.
    :param kind: list only the boards (serial and USB) simulating this board kind.

    While a board of a wired kit has no power, a board failing its handshake is logged
    and passed over instead of raising (``skip_failures``).
    """
    if timeout_scale is None:
        timeout_scale = max(kit.time_scale, MINIMUM_TIMEOUT_SCALE)
    simulators = {
        port_name(kit, simulator): simulator
        for simulator in kit.serial_simulators()
        if isinstance(simulator, serial_type) and _of_kind(kit, simulator, kind)
    }

    def list_ports() -> list[PortInfo]:
        return [
            PortInfo(
                device=name,
                vid=simulator.usb_vid,
                pid=simulator.usb_pid,
                serial_number=simulator.serial_number,
                manufacturer=simulator.manufacturer,
                product=simulator.product,
                description=f"simulated {type(simulator).__name__}",
            )
            for name, simulator in simulators.items()
            if simulator.connected
        ]

    async def open_port(port: str, baudrate: int) -> ByteStream:
        return SimulatorStream(simulators[port], name=port, time_scale=kit.time_scale)

    def find(*, find_all: bool, idVendor: int, idProduct: int) -> list[SimulatedUSBDevice]:  # noqa: N803
        return [
            SimulatedUSBDevice(simulator, kit)
            for simulator in kit.usb_simulators()
            if simulator.connected
            and _of_kind(kit, simulator, kind)
            and (simulator.idVendor, simulator.idProduct) == (idVendor, idProduct)
        ]

    mark_answers_at_once(find)  # (no thread to scan with)
    mark_answers_at_once(list_ports)
    wiring = kit.wiring
    return DiscoveryOptions(
        port_source=list_ports,
        opener=open_port,
        usb_finder=find,
        time_scale=timeout_scale,
        # A board without power is passed over (and logged), as discovery on the robot
        # passes over a motor board whose controller is silent: whoever looks for the
        # boards says so (KitRobot warns, naming the output to switch on).
        skip_failures=wiring is not None and not all(fed.powered for fed, _ in wiring.feeds),
        # Each simulated backend lists its own kind's boards only.
        identify_shared_ports=serial_type is SerialBoardSimulator and kind is None,
    )


def _of_kind(
    kit: SimulatedKit, simulator: SerialBoardSimulator | UsbBoardSimulator, kind: BoardKind | None
) -> bool:
    return kind is None or kit.kind_of(simulator) is kind


def _kind_of(backend: type) -> BoardKind:
    """The registered kind naming ``backend`` (or a class it derives from) as ``simulated``."""
    for cls in backend.__mro__:
        reference = f"{cls.__module__}:{cls.__qualname__}"
        for kind in board_kinds():
            if kind.backend_reference("simulated") == reference:
                return kind
    raise LookupError(
        f"{backend.__qualname__} is the simulated backend of no registered board kind: "
        "name it as one's simulated= backend"
    )


def kind_options(backend: type) -> DiscoveryOptions:
    """Discovery options finding the current kit's boards of ``backend``'s kind, and no others.

    A serial backend finds a port by its USB IDs, on a robot as in the simulated kit: if
    a simulator of the kind in the kit reports IDs that the backend's ``USB_IDS`` do not
    hold (none set, say), the backend would find none of its boards, so a
    :class:`UnmatchedSimulatorWarning` says so.

    :param backend: a simulated backend, named by a registered kind as its ``simulated``
        backend (or a subclass of one).
    :raises LookupError: no registered kind names it.
    """
    kit = current_kit()
    kind = _kind_of(backend)
    _check_usb_ids(kit, kind, backend)
    return kit_discovery_options(kit, kind=kind)


class KitDiscovery:
    """Makes a hardware backend find the current simulated kit's boards of its kind.

    The simulated backend of a serial or USB board is its hardware backend with this
    class first among its bases: its ``discover``, given no options, finds the boards of
    :func:`~j5aio.simulator.kit.current_kit` made from its kind's simulators
    (:func:`kind_options`), and from there on every call runs the hardware backend's own
    code over a simulated transport::

        class BeeSimulatedBackend(KitDiscovery, BeeHardwareBackend):
            "The Bee Board's hardware backend, on the simulated kit."
    """

    __slots__ = ()

    @classmethod
    def default_discovery_options(cls) -> DiscoveryOptions:
        """The current simulated kit's boards of this backend's kind (:func:`kind_options`)."""
        return kind_options(cls)


class UnmatchedSimulatorWarning(UserWarning):
    """A simulator of the kit is not found by its kind's backend: their USB IDs differ."""


def _check_usb_ids(kit: SimulatedKit, kind: BoardKind, backend: type) -> None:
    ids = getattr(backend, "USB_IDS", None)
    if ids is None:  # (not a serial backend)
        return
    for simulator in kit.serial_simulators():
        if kit.kind_of(simulator) is not kind or (simulator.usb_vid, simulator.usb_pid) in ids:
            continue
        given = ", ".join(f"{vid:04X}:{pid:04X}" for vid, pid in sorted(ids)) or "none"
        warnings.warn(
            f"board kind {kind.name!r}: its backend {backend.__qualname__} finds ports by "
            f"USB_IDS ({given}), and its simulator {simulator.serial_number} reports "
            f"{simulator.usb_vid:04X}:{simulator.usb_pid:04X}, so no board of the kind is "
            "found, on the simulated kit as on a robot: set the hardware backend's USB_IDS "
            "to the (vendor, product) IDs of the board's USB-serial adapter",
            UnmatchedSimulatorWarning,
            stacklevel=3,
        )
        return
