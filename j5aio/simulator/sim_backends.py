"""The simulated backends of j5aio's own serial and USB boards.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` made from its kind's simulators (see
:mod:`j5aio.simulator.discovery`), and nothing else: from there on every call runs the
hardware backend's own code (its polls included) over a simulated transport, as on a
robot. Each board kind names its simulated backend (``simulated=`` of
:class:`~j5aio.board_kinds.BoardKind`); the simulated environment imports this module the
first time it needs one of them.

A plugin's simulated backend is written the same way::

    class BeeSimulatedBackend(BeeBackend):
        @classmethod
        async def discover(cls, *, options=None):
            return await super().discover(options=options or kind_options(cls))
"""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.board_kinds import BoardKind, board_kinds
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduino2024Board, SBArduinoBoard
from j5aio.boards.sr.v4 import (
    Ruggeduino,
    SRArduinoBoard,
)

from .discovery import kit_discovery_options
from .kit import current_kit

__all__ = [
    "SBArduino2024SimulatedBackend",
    "SBArduinoSimulatedBackend",
    "SBServoBoardSimulatedBackend",
    "SRArduinoSimulatedBackend",
    "SRV4MotorBoardFw4SimulatedBackend",
    "SRV4MotorBoardSimulatedBackend",
    "SRV4PowerBoardFw4SimulatedBackend",
    "SRV4PowerBoardSimulatedBackend",
    "SRV4RuggeduinoSimulatedBackend",
    "SRV4ServoBoardFw4SimulatedBackend",
    "SRV4ServoBoardSimulatedBackend",
    "kind_options",
]


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

    :param backend: a simulated backend, named by a registered kind as its ``simulated``
        backend (or a subclass of one).
    :raises LookupError: no registered kind names it.
    """
    return kit_discovery_options(current_kit(), kind=_kind_of(backend))


class SRV4PowerBoardSimulatedBackend(SRV4PowerBoardHardwareBackend):
    """The SR v4 power board (firmware 3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4MotorBoardSimulatedBackend(SRV4MotorBoardHardwareBackend):
    """The SR v4 motor board (firmware 3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4ServoBoardSimulatedBackend(SRV4ServoBoardHardwareBackend):
    """The SR v4 servo board (firmware 2) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBArduinoSimulatedBackend(SBArduinoHardwareBackend):
    """The SourceBots Arduino (2019 firmware) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SBArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4RuggeduinoSimulatedBackend(SRV4RuggeduinoHardwareBackend):
    """The Ruggeduino (firmware 1) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Ruggeduino]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4PowerBoardFw4SimulatedBackend(SRV4PowerBoardFw4HardwareBackend):
    """The SR v4 power board (firmware 4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4MotorBoardFw4SimulatedBackend(SRV4MotorBoardFw4HardwareBackend):
    """The SR v4 motor board (firmware 4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4ServoBoardFw4SimulatedBackend(SRV4ServoBoardFw4HardwareBackend):
    """The SR v4 servo board (firmware 4.3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBServoBoardSimulatedBackend(SBServoBoardHardwareBackend):
    """The SourceBots servo board (firmware 4.4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRArduinoSimulatedBackend(SRArduinoHardwareBackend):
    """The SR Arduino (firmware 2) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SRArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBArduino2024SimulatedBackend(SBArduino2024HardwareBackend):
    """The SourceBots Arduino (sb2024 firmware) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(
        cls, *, options: DiscoveryOptions | None = None
    ) -> Sequence[SBArduino2024Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))
