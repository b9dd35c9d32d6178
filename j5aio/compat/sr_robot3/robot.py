"""sr-robot3's ``Robot``: finds the boards, powers the outputs, waits for the start.

It is built on j5aio's :class:`~j5aio.kit.KitRobot` through the sync facade: the boards
are j5aio's, found in the environment ``python -m j5aio run`` chose (the hardware, or the
simulated kit with ``--sim``), and they are made safe when the program ends.
"""

from __future__ import annotations

import logging
import os
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Final, TypeVar

from j5aio import __version__ as j5aio_version
from j5aio.compat.sr_robot3._kit import open_kit
from j5aio.compat.sr_robot3._logs import setup_logging
from j5aio.compat.sr_robot3.arduino import Arduino
from j5aio.compat.sr_robot3.astoria import RobotMode, robot_mode
from j5aio.compat.sr_robot3.camera import AprilCamera
from j5aio.compat.sr_robot3.exceptions import MetadataNotReadyError, end_of_match
from j5aio.compat.sr_robot3.kch import KCH
from j5aio.compat.sr_robot3.motor_board import MotorBoard
from j5aio.compat.sr_robot3.power_board import PowerBoard
from j5aio.compat.sr_robot3.raw_serial import RawSerial
from j5aio.compat.sr_robot3.servo_board import ServoBoard
from j5aio.compat.sr_robot3.utils import BoardIdentity, singular
from j5aio.competition.timer import add_game_over_hook
from j5aio.sync import ServoBoardFw4

if TYPE_CHECKING:
    from j5aio.sync import ArduinoUno, KitRobot

__all__ = ["SR_ROBOT3_VERSION", "Robot"]

#: The sr-robot3 release whose API this is.
SR_ROBOT3_VERSION: Final = "2026.0.3"

LOGGER = logging.getLogger("sr.robot3.robot")

B = TypeVar("B")


class Robot:
    """The robot: every board, found when it is made, and the start of the match.

    Only one robot may exist at a time on a computer: making a second raises
    ``OSError``. Unless ``wait_for_start`` is false, making it waits for the start
    (the start button, or ``--start-after`` / Enter under ``python -m j5aio run``).

    :param debug: log at DEBUG level on the console.
    :param wait_for_start: wait for the start before returning.
    :param trace_logging: log at TRACE level (below DEBUG) on the console.
    :param ignored_arduinos: serial numbers of Arduinos to leave out of
        :attr:`arduinos`.
    :param manual_boards: serial ports to look at for boards of each type, as sr-robot3
        takes them; j5aio finds boards by their USB identity, so these are only logged.
    :param raw_ports: ``(serial number, baud rate)`` of serial devices of the team's own
        to open (:attr:`raw_serial_devices`); not on the simulated kit.
    :param no_powerboard: run without a power board.
    """

    __slots__ = (
        "_arduinos", "_cameras", "_epoch", "_kch", "_kit", "_motor_boards", "_no_powerboard",
        "_power_board", "_raw_ports", "_servo_boards", "_started",
    )

    def __init_subclass__(cls, **kwargs: Any) -> None:
        raise TypeError(f"{cls.__name__} cannot be sub-classed.")

    def __init__(
        self,
        *,
        debug: bool = False,
        wait_for_start: bool = True,
        trace_logging: bool = False,
        ignored_arduinos: list[str] | None = None,
        manual_boards: dict[str, list[str]] | None = None,
        raw_ports: list[tuple[str, int]] | None = None,
        no_powerboard: bool = False,
    ) -> None:
        setup_logging(debug, trace_logging)
        LOGGER.info(f"sr.robot3 version {SR_ROBOT3_VERSION} (on j5aio {j5aio_version})")
        self._started = False
        self._no_powerboard = no_powerboard
        self._kit: KitRobot = open_kit(power_board_needed=not no_powerboard)
        add_game_over_hook(end_of_match)  # (in a match, game over then ends the program)
        self._epoch = time.time() - self._kit.time()
        if manual_boards:
            LOGGER.warning(
                "manual_boards is not needed on j5aio: boards are found by their USB "
                f"identity (ignoring {manual_boards!r})"
            )
        self._init_power_board()
        self._init_aux_boards(ignored_arduinos or [], raw_ports)
        self._log_connected_boards()
        if wait_for_start:
            LOGGER.debug("Waiting for start button.")
            self.wait_start()
        else:
            LOGGER.debug("Not waiting for start button.")

    def _init_power_board(self) -> None:
        """The power board, whose outputs KitRobot has switched on (but L2, the brain's).

        KitRobot does what sr-robot3 does at start-up: it finds the power board, switches
        every output on, then looks for the boards they feed.
        """
        if self._no_powerboard:
            return
        self._power_board = PowerBoard(self._kit.power_board)

    def _init_aux_boards(
        self, ignored_arduinos: list[str], raw_ports: list[tuple[str, int]] | None,
    ) -> None:
        kit = self._kit
        self._kch = KCH(kit.kch)
        self._motor_boards = MappingProxyType(
            {board.serial_number: MotorBoard(board) for board in kit.motor_boards})
        for servo_board in kit.servo_boards:
            # At the end, servos off as sr-robot3's reset does (on boards that can).
            servo_board.unpower_when_safe = isinstance(servo_board, ServoBoardFw4)
        self._servo_boards = MappingProxyType(
            {board.serial_number: ServoBoard(board) for board in kit.servo_boards})
        arduinos: dict[str, Arduino] = {}
        core_arduinos: list[ArduinoUno] = [*kit.arduinos, *kit.ruggeduinos]
        for board in core_arduinos:
            if board.serial_number not in ignored_arduinos:
                arduinos.setdefault(board.serial_number, Arduino(board))
        self._arduinos = MappingProxyType(arduinos)
        self._cameras = MappingProxyType({
            camera.serial_number: AprilCamera(camera.camera, camera.serial_number)
            for camera in kit.cameras
        })
        self._raw_ports: Mapping[str, RawSerial] = MappingProxyType({})
        if raw_ports:
            if self.is_simulated:
                LOGGER.warning("Raw ports are not available in the simulator.")
            else:
                self._raw_ports = RawSerial._get_supported_boards(raw_ports)

    def _log_connected_boards(self) -> None:
        """Log each board found: its type and serial (and, at DEBUG, its firmware)."""
        boards: list[Any] = [] if self._no_powerboard else [self._power_board]
        for group in (self._motor_boards, self._servo_boards, self._arduinos,
                      self._cameras, self._raw_ports):
            boards.extend(group.values())
        for board in boards:
            identity: BoardIdentity = board.identify()
            LOGGER.info(f"Found {type(board).__name__}, serial: {identity.asset_tag}")
            LOGGER.debug(
                f"Firmware Version of {identity.asset_tag}: {identity.sw_version}, "
                f"reported type: {identity.board_type}"
            )

    # -- the boards --------------------------------------------------------------------

    @property
    def kch(self) -> KCH:
        """The Raspberry Pi's HAT, with the user LEDs."""
        return self._kch

    @property
    def power_board(self) -> PowerBoard:
        """The power board.

        :raises RuntimeError: the robot was made with ``no_powerboard=True``.
        """
        if self._no_powerboard:
            raise RuntimeError("No power board was initialized")
        return self._power_board

    @property
    def motor_boards(self) -> Mapping[str, MotorBoard]:
        """The motor boards, by serial number."""
        return self._motor_boards

    @property
    def motor_board(self) -> MotorBoard:
        """The motor board. :raises RuntimeError: there is not exactly one."""
        return singular(self._motor_boards)

    @property
    def servo_boards(self) -> Mapping[str, ServoBoard]:
        """The servo boards, by serial number."""
        return self._servo_boards

    @property
    def servo_board(self) -> ServoBoard:
        """The servo board. :raises RuntimeError: there is not exactly one."""
        return singular(self._servo_boards)

    @property
    def arduinos(self) -> Mapping[str, Arduino]:
        """The Arduinos, by serial number."""
        return self._arduinos

    @property
    def arduino(self) -> Arduino:
        """The Arduino. :raises RuntimeError: there is not exactly one."""
        return singular(self._arduinos)

    @property
    def camera(self) -> AprilCamera:
        """The camera. :raises RuntimeError: there is not exactly one."""
        return singular(self._cameras)

    @property
    def raw_serial_devices(self) -> Mapping[str, RawSerial]:
        """The serial devices asked for with ``raw_ports``, by serial number."""
        return self._raw_ports

    # -- time ------------------------------------------------------------------------

    def sleep(self, secs: float) -> None:
        """Wait ``secs`` seconds (robot seconds: a simulated kit may run at another speed).

        :raises ValueError: ``secs`` is negative.
        """
        self._kit.sleep(secs)

    def time(self) -> float:
        """Seconds since the Unix epoch, by the robot's clock: use differences of it."""
        return self._epoch + self._kit.time()

    # -- the match -------------------------------------------------------------------

    @property
    def arena(self) -> str:
        """The arena the robot is in. :raises MetadataNotReadyError: before the start."""
        self._require_start()
        return self._kit.arena

    @property
    def zone(self) -> int:
        """The robot's starting zone. :raises MetadataNotReadyError: before the start."""
        self._require_start()
        return self._kit.zone

    @property
    def mode(self) -> RobotMode:
        """``COMP`` in a match, else ``DEV``. :raises MetadataNotReadyError: before the start."""
        self._require_start()
        return robot_mode(self._kit.mode)

    def _require_start(self) -> None:
        if not self._started:
            raise MetadataNotReadyError()

    @property
    def usbkey(self) -> Path:
        """Where the USB stick the code came from is mounted (else the program's folder)."""
        stick = self._kit.usb_stick
        if stick is not None:
            return stick
        named = os.environ.get("SBOT_USBKEY_PATH")
        if named:
            return Path(named)
        return Path(sys.argv[0]).resolve().parent if sys.argv and sys.argv[0] else Path.cwd()

    @property
    def is_simulated(self) -> bool:
        """Whether the robot runs on the simulated kit."""
        return self._kit.environment.name == "SimulatedEnvironment"

    def wait_start(self) -> None:
        """Wait for the start, then read the match's metadata and start its timer.

        While it waits, the power board beeps once, its run LED flashes (and the KCH's
        start LED); in a match (COMP mode) the robot stops when the match is over.
        """
        LOGGER.info("Waiting for start button.")
        if not self._started:
            self._kit.wait_start()
            self._epoch = time.time() - self._kit.time()
            self._started = True
            if self._kit.match_timer is not None:
                LOGGER.info(f"Timeout set: {self._kit.metadata.duration:g}s")
        else:
            self._wait_again()
        LOGGER.info("Start signal received; continuing.")

    def _wait_again(self) -> None:
        """A second wait for the start (sr-robot3 allows it): the start only, no new match."""
        from j5aio.competition.start import wait_for_start
        from j5aio.robot import BaseRobot
        from j5aio.sync.wrapping import call

        call(wait_for_start, BaseRobot.boards(), None)
