"""The simulated backends of j5aio's own serial and USB boards.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` (see :mod:`j5aio.simulator.discovery`); the
simulated power board's also listens to its simulator's start button instead of polling
it. The simulated environment (:mod:`j5aio.simulator.environment`) imports this module
the first time it needs one of them.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import Callable, Sequence

import anyio

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.boards.board import Board
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino

from .discovery import SimulatedUSBDevice, kit_discovery_options
from .kit import current_kit
from .sb_arduino_2019 import SBArduinoSimulator
from .sr_motor_fw3 import SRMotorBoardFw3Simulator
from .sr_power_fw3 import SRPowerBoardFw3Simulator
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

        hardware = _RUGGEDUINO_HARDWARE
        kind = next((k for k in board_kinds() if k.backend_reference("hardware") == hardware), None)
        return await super().discover(
            options=options
            or kit_discovery_options(current_kit(), SRRuggeduinoSimulator, kind=kind)
        )
