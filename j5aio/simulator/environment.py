"""SIMULATED_ENVIRONMENT: the hardware backends, connected to the simulated kit.

Each backend here *is* a hardware backend (a subclass of it) whose discovery looks at the
boards of :func:`~j5aio.simulator.kit.current_kit` instead of the computer's serial ports
and USB bus. Discovery, handshakes, protocol codecs and transports are the real ones:

- a serial board (motor board, Arduino) appears as a port named
  ``sim://<kit name>/<serial number>`` with its USB identity, and opening it gives a
  :class:`~j5aio.backends.hardware.transports.memory.SimulatorStream` to its simulator;
- a USB board (power board, servo board) is found as its simulator, which has the shape
  of a pyusb device, wrapped by :class:`SimulatedUSBDevice`.

So a program run on the simulated kit sends the same bytes as on a robot::

    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import KitConfig, use_kit

    kit = use_kit(KitConfig(motor_boards=1))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        print(kit.motor_boards[0].motors[0])    # what the simulated board now does

Unplugged simulators (``simulator.unplug()``) are not found, as on a real bus.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
import weakref
from collections.abc import Callable, Sequence
from typing import Any, cast

import anyio

from j5aio.backends.backend import Backend, BackendMeta
from j5aio.backends.environment import Environment
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.backends.hardware.transports.discovery import PortInfo
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.board_kinds import BoardKind, board_kinds
from j5aio.boards.board import Board
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino

from .base import SerialBoardSimulator, UsbBoardSimulator
from .kit import SimulatedKit, current_kit
from .sb_arduino_2019 import SBArduinoSimulator
from .sr_motor_fw3 import SRMotorBoardFw3Simulator
from .sr_power_fw3 import SRPowerBoardFw3Simulator
from .sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from .usb_support import no_device_error

__all__ = [
    "MINIMUM_TIMEOUT_SCALE",
    "SIMULATED_BACKENDS",
    "SIMULATED_ENVIRONMENT",
    "SBArduinoSimulatedBackend",
    "SRV4MotorBoardSimulatedBackend",
    "SRV4PowerBoardSimulatedBackend",
    "SRV4RuggeduinoSimulatedBackend",
    "SRV4ServoBoardSimulatedBackend",
    "SimulatedUSBDevice",
    "kit_discovery_options",
    "port_name",
    "simulated_backend",
]


def port_name(kit: SimulatedKit, simulator: SerialBoardSimulator) -> str:
    """Return the name a serial simulator's port has in ``kit``."""
    return f"sim://{kit.name}/{simulator.serial_number}"



# Piezo time on each simulated power board: when its notes last moved on.
_piezo_clocks: weakref.WeakKeyDictionary[SRPowerBoardFw3Simulator, float] = (
    weakref.WeakKeyDictionary()
)


class SimulatedUSBDevice:
    """A USB board simulator as discovery finds it, standing in for a pyusb device.

    Every attribute is the simulator's, with two additions: ``bus`` and ``address`` name
    its place in the kit (so that finding it again gives back the same board), and each
    transfer first lets the real time since the last one pass on a power board's piezo,
    so that queued notes finish playing.

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
        """Do a control transfer on the simulator, after letting time pass on it.

        A device found before the board was unplugged is dead for good (errno 19), as a
        pyusb device is after its cable came out, even once the board is back.
        """
        if self._simulator.connection != self._connection:
            raise no_device_error()
        self._let_time_pass()
        return self._simulator.ctrl_transfer(
            bmRequestType, bRequest, wValue, wIndex, data_or_wLength, timeout
        )

    def _let_time_pass(self) -> None:
        simulator = self._simulator
        if not isinstance(simulator, SRPowerBoardFw3Simulator):
            return
        now = time.monotonic()
        last = _piezo_clocks.get(simulator, now)
        elapsed_ms = int((now - last) * 1000)
        if elapsed_ms > 0 or simulator not in _piezo_clocks:
            simulator.advance_piezo(elapsed_ms)
            _piezo_clocks[simulator] = last + elapsed_ms / 1000

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
        :data:`MINIMUM_TIMEOUT_SCALE`.
    :param kind: list only the boards (serial and USB) simulating this board kind.
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

    return DiscoveryOptions(
        port_source=list_ports,
        opener=open_port,
        usb_finder=find,
        time_scale=timeout_scale,
        # Each simulated backend lists its own kind's boards only.
        identify_shared_ports=serial_type is SerialBoardSimulator and kind is None,
    )


def _of_kind(
    kit: SimulatedKit, simulator: SerialBoardSimulator | UsbBoardSimulator, kind: BoardKind | None
) -> bool:
    return kind is None or kit.kind_of(simulator) is kind


class SRV4PowerBoardSimulatedBackend(SRV4PowerBoardHardwareBackend):
    """The SR v4 power board hardware backend, finding the simulated kit's power boards."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the power boards of the current simulated kit (or where ``options`` say)."""
        return await super().discover(options=options or kit_discovery_options(current_kit()))

    async def _poll_button(self, report: Callable[[], None], *, fresh: bool) -> None:
        """Read the button once, then listen to the simulator instead of polling it.

        The simulator tells when its button goes down (a board on a real bus must be
        asked), so a wait costs no CPU and ends as soon as the button is pressed.
        """
        device = self._link.device
        simulator = device.simulator if isinstance(device, SimulatedUSBDevice) else None
        if isinstance(simulator, SRPowerBoardFw3Simulator):
            await self._listen_to_button(simulator, report)
        else:
            await super()._poll_button(report, fresh=fresh)

    async def _listen_to_button(
        self, simulator: SRPowerBoardFw3Simulator, report: Callable[[], None]
    ) -> None:
        loop = asyncio.get_running_loop()
        pressed = anyio.Event()

        def on_press() -> None:  # in the thread that pressed the button
            with contextlib.suppress(RuntimeError):  # the loop has closed: nobody waits
                loop.call_soon_threadsafe(pressed.set)

        stop = simulator.watch_start_button(on_press)
        try:
            if not await self.get_button_state(0):  # held already: a read over the link
                await pressed.wait()
            report()
        finally:
            stop()


class SRV4ServoBoardSimulatedBackend(SRV4ServoBoardHardwareBackend):
    """The SR v4 servo board hardware backend, finding the simulated kit's servo boards."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the servo boards of the current simulated kit (or where ``options`` say)."""
        return await super().discover(options=options or kit_discovery_options(current_kit()))


class SRV4MotorBoardSimulatedBackend(SRV4MotorBoardHardwareBackend):
    """The SR v4 motor board hardware backend, finding the simulated kit's motor boards."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the motor boards of the current simulated kit (or where ``options`` say)."""
        return await super().discover(
            options=options or kit_discovery_options(current_kit(), SRMotorBoardFw3Simulator)
        )


class SBArduinoSimulatedBackend(SBArduinoHardwareBackend):
    """The SourceBots Arduino hardware backend, finding the simulated kit's Arduinos."""

    @classmethod
    async def discover(
        cls, *, options: DiscoveryOptions | None = None,
    ) -> Sequence[SBArduinoBoard]:
        """Find the SourceBots Arduinos of the current simulated kit (or where ``options`` say)."""
        return await super().discover(
            options=options or kit_discovery_options(current_kit(), SBArduinoSimulator)
        )


class SRV4RuggeduinoSimulatedBackend(SRV4RuggeduinoHardwareBackend):
    """The Ruggeduino hardware backend, finding the simulated kit's Ruggeduinos."""

    @classmethod
    async def discover(
        cls, *, options: DiscoveryOptions | None = None,
    ) -> Sequence[Ruggeduino]:
        """Find the Ruggeduinos of the current simulated kit (or where ``options`` say).

        Only the simulators standing in for a firmware 1 Ruggeduino: the SR Arduino's
        simulator (firmware 2) is the same class, and is found by its own kind.
        """
        from j5aio.board_kinds import board_kinds

        kind = next(
            (k for k in board_kinds() if k.hardware is SRV4RuggeduinoHardwareBackend), None
        )
        return await super().discover(
            options=options
            or kit_discovery_options(current_kit(), SRRuggeduinoSimulator, kind=kind)
        )


#: The simulated backends of j5aio's own board kinds, by their hardware backend.
_NAMED_SIMULATED_BACKENDS: dict[type[Backend], type[Backend]] = {
    SRV4PowerBoardHardwareBackend: SRV4PowerBoardSimulatedBackend,
    SRV4MotorBoardHardwareBackend: SRV4MotorBoardSimulatedBackend,
    SRV4ServoBoardHardwareBackend: SRV4ServoBoardSimulatedBackend,
    SBArduinoHardwareBackend: SBArduinoSimulatedBackend,
    SRV4RuggeduinoHardwareBackend: SRV4RuggeduinoSimulatedBackend,
}


def simulated_backend(kind: BoardKind) -> type[Backend] | None:
    """Return the backend that finds ``kind``'s boards in the current simulated kit.

    That is the kind's own ``simulated`` backend (:class:`~j5aio.board_kinds.BoardKind`) if it
    has one, else a subclass of its hardware backend whose ``discover`` looks at the
    boards of :func:`~j5aio.simulator.kit.current_kit` made from the kind's simulators
    (the hardware backend's ``discover`` must take ``options``, as the serial and USB
    hardware backends' do). ``None`` for a kind with no simulator or no backend.
    """
    if kind.simulated is not None:
        return kind.simulated
    hardware = kind.hardware
    if hardware is None or not kind.simulators:
        return None
    named = _NAMED_SIMULATED_BACKENDS.get(hardware)
    if named is not None:
        return named

    async def discover(
        cls: type[Backend], *, options: DiscoveryOptions | None = None
    ) -> Sequence[Board]:
        parent: Any = super(derived, cls)  # a hardware backend: discover takes options
        found: Sequence[Board] = await parent.discover(
            options=options or kit_discovery_options(current_kit(), kind=kind)
        )
        return found

    derived = cast(type[Backend], BackendMeta(
        f"{hardware.__name__}Simulated",
        (hardware,),
        {
            "__doc__": f"{hardware.__name__}, finding the simulated kit's {kind.description}.",
            "__module__": hardware.__module__,
            "discover": classmethod(discover),
        },
    ))
    _NAMED_SIMULATED_BACKENDS[hardware] = derived
    return derived


#: Every simulated backend, one per registered board kind with a simulator.
SIMULATED_BACKENDS: tuple[type[Backend], ...] = tuple(
    backend
    for backend in (simulated_backend(kind) for kind in board_kinds())
    if backend is not None
)

#: The simulated kit: the hardware backends, talking to the boards of
#: :func:`~j5aio.simulator.kit.current_kit`.
SIMULATED_ENVIRONMENT = Environment.from_backends("SimulatedEnvironment", SIMULATED_BACKENDS)
