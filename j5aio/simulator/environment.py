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

Each kind's backend is imported the first time a board of its class is asked for while
the current kit has simulators of that kind; a kind the kit has none of gives no boards
without being imported or asked (a group made then keeps finding none, even once
:func:`~j5aio.simulator.kit.use_kit` has changed the kit: ask the environment again).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, cast

from j5aio.backends.environment import Environment
from j5aio.board_kinds import BoardKind, board_kinds

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.backends.hardware.options import DiscoveryOptions
    from j5aio.boards.board import Board

    from .discovery import (
        MINIMUM_TIMEOUT_SCALE,
        SimulatedUSBDevice,
        kit_discovery_options,
        port_name,
    )
    from .sim_backends import (
        SBArduinoSimulatedBackend,
        SRV4MotorBoardSimulatedBackend,
        SRV4PowerBoardSimulatedBackend,
        SRV4RuggeduinoSimulatedBackend,
        SRV4ServoBoardSimulatedBackend,
    )

    #: Every simulated backend, one per registered board kind with a simulator (reading
    #: it imports them all).
    SIMULATED_BACKENDS: tuple[type[Backend], ...]

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

# Where the names this module exports live; each is imported when first looked up here.
_EXPORTS: dict[str, str] = {
    **dict.fromkeys(
        ("MINIMUM_TIMEOUT_SCALE", "SimulatedUSBDevice", "kit_discovery_options", "port_name"),
        "j5aio.simulator.discovery",
    ),
    **dict.fromkeys(
        (
            "SBArduinoSimulatedBackend",
            "SRV4MotorBoardSimulatedBackend",
            "SRV4PowerBoardSimulatedBackend",
            "SRV4RuggeduinoSimulatedBackend",
            "SRV4ServoBoardSimulatedBackend",
        ),
        "j5aio.simulator.sim_backends",
    ),
}

_SIM_BACKENDS = "j5aio.simulator.sim_backends"

#: The simulated backends of j5aio's own board kinds, by their hardware backend's import
#: path (no module is imported until a board of the kind is wanted).
_NAMED_SIMULATED_BACKENDS: dict[str, str] = {
    "j5aio.backends.hardware.sr.v4.power_board:SRV4PowerBoardHardwareBackend":
        "SRV4PowerBoardSimulatedBackend",
    "j5aio.backends.hardware.sr.v4.motor_board:SRV4MotorBoardHardwareBackend":
        "SRV4MotorBoardSimulatedBackend",
    "j5aio.backends.hardware.sr.v4.servo_board:SRV4ServoBoardHardwareBackend":
        "SRV4ServoBoardSimulatedBackend",
    "j5aio.backends.hardware.sb.arduino:SBArduinoHardwareBackend": "SBArduinoSimulatedBackend",
    "j5aio.backends.hardware.sr.v4.ruggeduino:SRV4RuggeduinoHardwareBackend":
        "SRV4RuggeduinoSimulatedBackend",
}

#: The simulated backends made so far for kinds without a named one, by hardware backend.
_DERIVED: dict[type[Backend], type[Backend]] = {}


def _has_simulated_backend(kind: BoardKind) -> bool:
    """Whether ``kind`` has a simulated backend, importing nothing."""
    if kind.backend_reference("simulated") is not None:
        return True
    return kind.backend_reference("hardware") is not None and bool(kind.simulators)


def simulated_backend(kind: BoardKind) -> type[Backend] | None:
    """Return the backend that finds ``kind``'s boards in the current simulated kit.

    That is the kind's own ``simulated`` backend (:class:`~j5aio.board_kinds.BoardKind`) if it
    has one, else a subclass of its hardware backend whose ``discover`` looks at the
    boards of :func:`~j5aio.simulator.kit.current_kit` made from the kind's simulators
    (the hardware backend's ``discover`` must take ``options``, as the serial and USB
    hardware backends' do). ``None`` for a kind with no simulator or no backend.
    Only the modules of that backend are imported.
    """
    if not _has_simulated_backend(kind):
        return None
    if kind.backend_reference("simulated") is not None:
        return kind.simulated
    named = _NAMED_SIMULATED_BACKENDS.get(kind.backend_reference("hardware") or "")
    if named is not None:
        import importlib

        backend: type[Backend] = getattr(importlib.import_module(_SIM_BACKENDS), named)
        return backend
    hardware = kind.hardware
    assert hardware is not None
    derived = _DERIVED.get(hardware)
    if derived is None:
        derived = _derive(kind, hardware)
        _DERIVED[hardware] = derived
    return derived


def _derive(kind: BoardKind, hardware: type[Backend]) -> type[Backend]:
    from j5aio.backends.backend import BackendMeta

    from .discovery import kit_discovery_options
    from .kit import current_kit

    async def discover(
        cls: type[Backend], *, options: DiscoveryOptions | None = None
    ) -> Sequence[Board]:
        parent: Any = super(derived, cls)  # a hardware backend: discover takes options
        found: Sequence[Board] = await parent.discover(
            options=options or kit_discovery_options(current_kit(), kind=kind)
        )
        return found

    derived = cast("type[Backend]", BackendMeta(
        f"{hardware.__name__}Simulated",
        (hardware,),
        {
            "__doc__": f"{hardware.__name__}, finding the simulated kit's {kind.description}.",
            "__module__": hardware.__module__,
            "discover": classmethod(discover),
        },
    ))
    return derived


def _loader(kind: BoardKind) -> Callable[[], type[Backend]]:
    def load() -> type[Backend]:
        backend = simulated_backend(kind)
        assert backend is not None  # (only kinds with one are registered)
        return backend

    return load


def _idle(kind: BoardKind) -> Callable[[], bool] | None:
    """For a kind with simulators: whether the current kit has none of them.

    Its backend finds its boards among the kit's simulators (a kind's own ``simulated``
    backend too: see :data:`~j5aio.board_kinds.SimulatorFactory`), so it is neither
    imported nor asked while the kit has none. A kind without simulators (the camera,
    which every kit has) is always asked.
    """
    if not kind.simulators:
        return None

    def idle() -> bool:
        from .kit import current_kit

        kit = current_kit()
        return not any(kit.simulators(entry.name) for entry in kind.simulators)

    return idle


def _make_environment() -> Environment:
    environment = Environment("SimulatedEnvironment")
    for kind in board_kinds():
        if _has_simulated_backend(kind):
            environment.register_lazily(kind.board, _loader(kind), idle=_idle(kind))
    return environment


#: The simulated kit: the hardware backends, talking to the boards of
#: :func:`~j5aio.simulator.kit.current_kit`. Each kind's backend is imported the first time
#: a board of its class is asked for while the current kit has such boards.
SIMULATED_ENVIRONMENT = _make_environment()


def __getattr__(name: str) -> Any:  # PEP 562: the exports above, imported on first use
    if name == "SIMULATED_BACKENDS":
        value: Any = tuple(SIMULATED_ENVIRONMENT.backends)
    elif name in _EXPORTS:
        import importlib

        value = getattr(importlib.import_module(_EXPORTS[name]), name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
