"""The simulated backends of j5aio's own serial and USB boards.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` (see :mod:`j5aio.simulator.discovery`), and
nothing else: from there on every call runs the hardware backend's own code (its polls
included) over a simulated transport, as on a robot. The simulated environment
(:mod:`j5aio.simulator.environment`) imports this module the first time it needs one of
them.
"""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.boards.board import Board
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino

from .discovery import kit_discovery_options
from .kit import current_kit
from .sb_arduino_2019 import SBArduinoSimulator
from .sr_motor_fw3 import SRMotorBoardFw3Simulator
from .sr_ruggeduino_fw1 import SRRuggeduinoSimulator

_RUGGEDUINO_HARDWARE = (
    f"{SRV4RuggeduinoHardwareBackend.__module__}:{SRV4RuggeduinoHardwareBackend.__qualname__}"
)

__all__ = [
    "SBArduinoSimulatedBackend",
    "SRV4MotorBoardSimulatedBackend",
    "SRV4PowerBoardSimulatedBackend",
    "SRV4RuggeduinoSimulatedBackend",
    "SRV4ServoBoardSimulatedBackend",
]


class SRV4PowerBoardSimulatedBackend(SRV4PowerBoardHardwareBackend):
    """The SR v4 power board hardware backend, finding the simulated kit's power boards."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the power boards of the current simulated kit (or where ``options`` say)."""
        return await super().discover(options=options or kit_discovery_options(current_kit()))


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

        hardware = _RUGGEDUINO_HARDWARE
        kind = next((k for k in board_kinds() if k.backend_reference("hardware") == hardware), None)
        return await super().discover(
            options=options
            or kit_discovery_options(current_kit(), SRRuggeduinoSimulator, kind=kind)
        )
