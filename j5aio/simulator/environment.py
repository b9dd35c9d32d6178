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

Each kind names its simulated backend (``simulated=`` of
:class:`~j5aio.board_kinds.BoardKind`), imported the first time a board of its class is
asked for while the current kit has simulators of that kind; a kind the kit has none of
gives no boards without being imported or asked (a group made then keeps finding none, even once
:func:`~j5aio.simulator.kit.use_kit` has changed the kit: ask the environment again).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from j5aio._lazy import lazy_exports
from j5aio.backends.environment import Environment
from j5aio.board_kinds import BoardKind, board_kinds

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend

    from .discovery import (
        MINIMUM_TIMEOUT_SCALE,
        SimulatedUSBDevice,
        kit_discovery_options,
        port_name,
    )
    from .kit import SimulatedKit
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
_exported, _ = lazy_exports(
    __name__,
    {
        "j5aio.simulator.discovery": [
            "MINIMUM_TIMEOUT_SCALE",
            "SimulatedUSBDevice",
            "kit_discovery_options",
            "port_name",
        ],
        "j5aio.simulator.sim_backends": [
            "SBArduinoSimulatedBackend",
            "SRV4MotorBoardSimulatedBackend",
            "SRV4PowerBoardSimulatedBackend",
            "SRV4RuggeduinoSimulatedBackend",
            "SRV4ServoBoardSimulatedBackend",
        ],
    },
)


def _has_simulated_backend(kind: BoardKind) -> bool:
    """Whether ``kind`` names a simulated backend, importing nothing."""
    return kind.backend_reference("simulated") is not None


def simulated_backend(kind: BoardKind) -> type[Backend] | None:
    """Return the backend that finds ``kind``'s boards in the current simulated kit.

    That is the backend the kind names as ``simulated`` (:class:`~j5aio.board_kinds.BoardKind`;
    j5aio's serial and USB boards' are in :mod:`j5aio.simulator.sim_backends`), or
    ``None`` for a kind that names none. Only the modules of that backend are imported.
    """
    return kind.simulated


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
    names = tuple(entry.name for entry in kind.simulators)

    def idle() -> bool:
        kit = _current_kit_function()()
        return not any(kit.simulators(name) for name in names)

    return idle


@functools.cache
def _current_kit_function() -> Callable[[], SimulatedKit]:
    """:func:`~j5aio.simulator.kit.current_kit`, its module imported on the first call.

    (Kept: an environment asks each kind whether it is idle at each search, and importing
    a name from a module again costs each time.)
    """
    from .kit import current_kit

    return current_kit


def _make_environment() -> Environment:
    environment = Environment("SimulatedEnvironment")
    for kind in board_kinds():
        if _has_simulated_backend(kind):
            # (by its path: a board class the kit has none of is never imported)
            environment._register_lazily_by_path(
                kind.board_reference(), _loader(kind), idle=_idle(kind)
            )
    return environment


#: The simulated kit: the hardware backends, talking to the boards of
#: :func:`~j5aio.simulator.kit.current_kit`. Each kind's backend is imported the first time
#: a board of its class is asked for while the current kit has such boards.
SIMULATED_ENVIRONMENT = _make_environment()


def __getattr__(name: str) -> Any:  # PEP 562: the exports above, imported on first use
    if name != "SIMULATED_BACKENDS":
        return _exported(name)
    value = globals()[name] = tuple(SIMULATED_ENVIRONMENT.backends)
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
