"""KitRobot: a ready-made robot for the Student Robotics v4 and SourceBots kit.

::

    from j5aio.kit import KitRobot

    async with KitRobot() as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        volts = await robot.power_board.battery_sensor.get_voltage()

On match day, ``await robot.wait_start()`` waits for the start button and reads the
match's zone and arena (see :doc:`/match-day`).

Its boards are found through the environment passed in, or else the default one (real
hardware, unless ``J5AIO_ENV`` or ``python -m j5aio run --sim`` chose otherwise: see
:mod:`j5aio.environments`).

It powers the kit up as the kit needs: the motor and servo boards take their 12 V from
the power board's outputs, so it finds the power board first, switches those outputs
on, waits for the boards to boot, and then looks for them (see :mod:`j5aio.kit_power`).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from types import TracebackType
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

import anyio

from j5aio import kit_power
from j5aio.backends.environment import Environment
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.boards.camera import CameraBoard
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard
from j5aio.components.marker_camera import MarkerCamera
from j5aio.environments import get_default_environment, hint_no_hardware
from j5aio.robot import BaseRobot

if TYPE_CHECKING:
    from j5aio.boards.arduino.all_digital import AllDigitalUno
    from j5aio.boards.sr.kch import KCHBoard
    from j5aio.boards.sr.v4 import ServoBoardFw4
    from j5aio.view import LiveView

BoardT = TypeVar("BoardT", bound=Board)

#: The KCH's board class, by its path (imported where a KCH may be found).
_KCH_BOARD = "j5aio.boards.sr.kch:KCHBoard"
#: The all-digital Arduinos' board class, by its path (imported where one may be found).
_ALL_DIGITAL_UNO = "j5aio.boards.arduino.all_digital:AllDigitalUno"

__all__ = ["KitRobot"]


class KitRobot(BaseRobot):
    """A robot built from an SR v4 power board and any SR v4 / SourceBots boards beside it.

    After ``async with KitRobot() as robot`` it has:

    - ``robot.power_board``: the one power board (an error says so if there is not
      exactly one);
    - ``robot.motor_boards``, ``robot.servo_boards`` and ``robot.arduinos``: groups of
      every such board found, possibly empty, reached by position or serial number.
      ``robot.arduinos`` holds the kit's Arduinos whatever their firmware (the SR
      Arduino, firmware 2; the SourceBots Arduinos of 2019 and 2024), each with
      ``pins`` and ``ultrasound_sensors``; ``robot.ruggeduinos`` holds the SR ones (the
      Ruggeduino of the 2019 kit, the SR Arduino), as in j5's programs. Indexing an
      empty group says which groups do have boards;
    - ``robot.cameras``: the cameras found (webcams; the simulated kit's camera), and
      ``robot.camera``: the first one's :class:`~j5aio.components.marker_camera.MarkerCamera`
      (``None`` without a camera), so that ``await robot.camera.see()`` finds markers;
    - ``robot.kch``: the KCH, the Student Robotics HAT on the Raspberry Pi of the 2023+
      kit, with its user RGB LEDs and start LED (``None`` without one: on any other
      computer, and on a simulated kit that has none, such as ``sr2019``).

    Through :mod:`j5aio.sync` (``from j5aio.sync import KitRobot``), ``robot = KitRobot()``
    finds the boards at once, with no ``async with``, and they are made safe when the
    program ends.

    Start-up powers the kit as sr-robot3 and sbot do: the power board is found first,
    the outputs in ``power_on`` are switched on (by default every output but L2, which
    powers the brain), and after :data:`~j5aio.kit_power.POWER_UP_WAIT` seconds for the
    boards they feed to boot (scaled by a simulated kit's time scale) the other boards
    are looked for. A motor board that is plugged in but stays silent, or a servo board
    that reports no 12 V, gets a :class:`~j5aio.kit_power.KitPowerWarning` naming the
    output to switch on.

    :param environment: where to find the boards; the default environment if omitted.
    :param boards: more boards to hold, a plugin's say, as ``{"bees": BeeBoard}``: each
        group of that board class is found with the kit's own (after the power-up) and
        held as the attribute of that name (``robot.bees``), and by
        :meth:`~j5aio.kit.KitRobot.board_group` (``robot.board_group(BeeBoard)``,
        typed), and is made safe at the end with the others.
    :param view: serve the live view of the boards while the robot runs (see
        :mod:`j5aio.view`; needs the ``view`` extra). ``None`` (the default) follows
        ``J5AIO_VIEW``. A view already running (``python -m j5aio run --view`` starts
        one) shows this robot's boards, and no second one is started.
    :param power_on: the power board outputs to switch on at start-up: ``True`` (the
        default) for every output but L2, ``False`` for none (the boards they feed
        will then not work), or the outputs, by name (``"H0"``, ``"L1"``, ``"5V"``) or
        number. L2 is the brain's and cannot be chosen.
    :param wait_for_start: wait for the start of the match once the boards are found,
        as sr-robot3's ``Robot()`` and ``import sbot`` do (see :doc:`/match-day`); the
        default, ``False``, returns at once and :meth:`~j5aio.robot.BaseRobot.wait_start`
        waits later.
    :raises TypeError: ``environment`` is not an Environment, ``power_on`` is not
        one of those, ``wait_for_start`` is not a bool, or ``boards`` is not a mapping of
        names to board classes.
    :raises ValueError: ``power_on`` names an output that does not exist, or L2; a name
        in ``boards`` is not an identifier, or is one of the robot's own attributes.
    """

    #: Seconds to wait for the boards to boot once their outputs are on (hardware; a
    #: simulated kit scales it by its time scale).
    POWER_UP_WAIT: ClassVar[float] = kit_power.POWER_UP_WAIT

    power_board: PowerBoard
    power_boards: BoardGroup[PowerBoard]
    motor_boards: BoardGroup[MotorBoard]
    servo_boards: BoardGroup[ServoBoard]
    arduinos: BoardGroup[SBArduinoBoard | AllDigitalUno]
    ruggeduinos: BoardGroup[Ruggeduino]
    cameras: BoardGroup[CameraBoard]
    camera: MarkerCamera | None
    kch: KCHBoard | None

    def __init__(
        self,
        *,
        environment: Environment | None = None,
        boards: Mapping[str, type[Board]] | None = None,
        view: bool | None = None,
        power_on: kit_power.PowerOnChoice = True,
        wait_for_start: bool = False,
    ) -> None:
        if environment is not None and not isinstance(environment, Environment):
            self.release_lock()
            raise TypeError(
                f"environment must be an Environment (such as SIMULATED_ENVIRONMENT), "
                f"not {type(environment).__name__}"
            )
        try:
            self._power_on = kit_power.check_power_on(power_on)
            self._more_boards = _check_more_boards(boards)
        except (TypeError, ValueError):
            self.release_lock()
            raise
        self._held: dict[type[Board], BoardGroup[Any]] = {}
        super().__init__(wait_for_start=wait_for_start)
        self._environment = environment
        self._chosen_by_default = environment is None
        self._view_wanted = view
        self._view: LiveView | None = None
        self._power_messages: list[str] = []

    @property
    def environment(self) -> Environment:
        """The environment the boards are found in."""
        if self._environment is None:
            self._environment = get_default_environment()
        return self._environment

    async def setup(self) -> None:
        """Find the power board, power the kit up, then find every other board.

        :raises CommunicationError: there is not exactly one power board, or a board
            could not be reached. When the hardware was looked at only by default and
            nothing was found (or it could not be looked at), one line says how to run
            on the simulated kit instead.
        """
        environment = self.environment
        self._start_view()
        kit_power.wire_simulated_kit(environment)  # (the simulated kit: as the robot is)
        self.power_boards = await environment.get_board_group(PowerBoard)
        if len(self.power_boards) == 1:
            await self._power_up(self.power_boards.singular())
        self.motor_boards = await environment.get_board_group(MotorBoard)
        self.servo_boards = await environment.get_board_group(ServoBoard)
        self.arduinos = await self._find_arduinos(environment)
        self.ruggeduinos = await environment.get_board_group(Ruggeduino)
        if environment._has_backend_for(CameraBoard):
            self.cameras = await environment.get_board_group(CameraBoard)
        else:
            # (imported here: the camera backends bring the vision modules with them)
            from j5aio.backends.camera.files import FileCameraBackend

            self.cameras = BoardGroup(CameraBoard, FileCameraBackend)
        self.camera = self.cameras[0].camera if self.cameras else None
        self.kch = await self._find_kch(environment)
        for name, board in self._more_boards.items():
            group = await environment.get_board_group(board)
            self._held[board] = group
            setattr(self, name, group)
        groups = (
            self.power_boards,
            self.motor_boards,
            self.servo_boards,
            self.arduinos,
            self.ruggeduinos,
        )
        if self._chosen_by_default and not any(groups):
            hint_no_hardware()
        self.power_board = self.power_boards.singular()
        await self._warn_about_power()
        self._explain_empty_groups()

    async def _power_up(self, power_board: PowerBoard) -> None:
        """Switch on the outputs feeding the kit's boards, and give those boards time to boot."""
        outputs = kit_power.outputs_to_switch_on(self._power_on, power_board)
        for number in outputs:
            await power_board.outputs[number].set_is_enabled(True)
        if outputs:
            wait = kit_power.boot_wait(self.environment, self.POWER_UP_WAIT)
            # The console kit says what it does. (Its module is looked up, not imported:
            # a board can only be on a console backend once that module is loaded.)
            console = sys.modules.get("j5aio.backends.console.backend")
            backend = power_board.backend
            if console is not None and isinstance(backend, console.ConsoleBackend):
                await backend.console.info(kit_power.power_up_message(outputs, wait))
            await anyio.sleep(wait)

    async def _warn_about_power(self) -> None:
        """Warn about each board that seems to have no power, naming its output."""
        environment = self.environment
        kit_power.remember_feeding(kit_power.feeding_outputs(environment))
        silent = await kit_power.silent_motor_boards(
            environment, (board.serial_number for board in self.motor_boards)
        )
        # (a firmware-4 servo board exists only once its module is loaded)
        fw4 = sys.modules.get("j5aio.boards.sr.v4.servo_board_fw4")
        fw4_class: type[ServoBoardFw4] | None = fw4.ServoBoardFw4 if fw4 is not None else None
        unpowered = [
            board.serial_number
            for board in self.servo_boards
            if fw4_class is not None
            and isinstance(board, fw4_class)
            and not await board.power_good.get_state()
        ]
        said = {*silent, *unpowered}
        found = {board.serial_number for board in (*self.motor_boards, *self.servo_boards)}
        missing = [  # (the simulated kit knows which boards it left without power)
            serial
            for serial in kit_power.unpowered_simulated_boards(environment)
            if serial not in said and serial not in found
        ]
        if silent or unpowered or missing:
            self._power_messages = kit_power.warn_unpowered(
                silent,
                unpowered,
                kit_power.feeding_outputs(environment),
                missing_boards=missing,
            )
            self._show_in_view(self._power_messages)

    @staticmethod
    def _show_in_view(messages: list[str]) -> None:
        """Put ``messages`` in the live view's log, if a view is running."""
        from j5aio.view import current_view

        view = current_view()
        if view is not None:
            for message in messages:
                view.state.add_log_line("power", message)

    def board_group(self, board: type[BoardT]) -> BoardGroup[BoardT]:
        """Return the group of ``board`` that ``boards=`` asked the robot to hold.

        :raises KeyError: ``boards`` did not name that board class (or the robot is not
            set up yet).
        """
        try:
            return self._held[board]
        except KeyError:
            held = ", ".join(held.__name__ for held in self._held) or "none"
            raise KeyError(
                f"the robot holds no group of {getattr(board, '__name__', board)!r}: give it "
                f"in KitRobot(boards={{...}}); it holds: {held}"
            ) from None

    def _explain_empty_groups(self) -> None:
        """Make indexing an empty group say which groups have boards (and why it may be empty)."""
        named: dict[str, BoardGroup[Any]] = {
            "robot.power_boards": self.power_boards,
            "robot.motor_boards": self.motor_boards,
            "robot.servo_boards": self.servo_boards,
            "robot.arduinos": self.arduinos,
            "robot.ruggeduinos": self.ruggeduinos,
            "robot.cameras": self.cameras,
            **{f"robot.{name}": self._held[board] for name, board in self._more_boards.items()},
        }
        filled = [f"{name} ({len(group)})" for name, group in named.items() if group]
        elsewhere = f"boards were found in {', '.join(filled)}" if filled else "no board was found"
        power = " ".join(
            message if message.endswith(".") else f"{message}." for message in self._power_messages
        )
        for name, group in named.items():
            if not group:
                group.empty_hint = f"{name} is empty; {elsewhere}." + (f" {power}" if power else "")

    @staticmethod
    async def _find_arduinos(
        environment: Environment,
    ) -> BoardGroup[SBArduinoBoard | AllDigitalUno]:
        """The Arduinos of every firmware of today's and the 2019 kits, in one group."""
        groups: list[BoardGroup[Any]] = [await environment.get_board_group(SBArduinoBoard)]
        # (an environment that finds one board of each class asked, the console, is
        # asked for the SourceBots Arduino alone, as before)
        if environment.gather and environment._might_find_named(_ALL_DIGITAL_UNO):
            from j5aio.boards.arduino.all_digital import AllDigitalUno

            groups.append(await environment.get_board_group(AllDigitalUno))
        return BoardGroup.of_groups(ArduinoUno, groups)

    @staticmethod
    async def _find_kch(environment: Environment) -> KCHBoard | None:
        """The KCH, if the environment can find one and there is one (a Pi has one HAT)."""
        # (neither its backend nor, on the simulated kit, its class is loaded otherwise)
        if not environment._might_find_named(_KCH_BOARD):
            return None
        from j5aio.boards.sr.kch import KCHBoard

        found = await environment.get_board_group(KCHBoard)
        return found[0] if found else None

    # --- the live view (j5aio.view): started in setup, stopped on the way out ---

    def _start_view(self) -> None:
        if self._view_wanted is False or not (self._view_wanted or os.environ.get("J5AIO_VIEW")):
            return  # (no view asked for, J5AIO_VIEW unset: its module is not even imported)
        from j5aio.view import current_view, start_view, view_requested

        wanted = self._view_wanted if self._view_wanted is not None else view_requested()
        if wanted and self._view is None and current_view() is None:
            self._view = start_view()  # (a view already running, the CLI's, shows the robot)

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> bool:
        try:
            return await super().__aexit__(exc_type, exc, traceback)
        finally:
            if self._view is not None:
                self._view.close()
                self._view = None


def _check_more_boards(boards: object) -> dict[str, type[Board]]:
    """The ``boards=`` of :class:`KitRobot`, checked: names that are free, and board classes."""
    if boards is None:
        return {}
    if not isinstance(boards, Mapping):
        raise TypeError(
            "boards must map attribute names to board classes, such as "
            f"{{'bees': BeeBoard}}, not {type(boards).__name__}"
        )
    checked: dict[str, type[Board]] = {}
    for name, board in boards.items():
        if not isinstance(name, str) or not name.isidentifier() or name.startswith("_"):
            raise ValueError(
                f"boards: {name!r} cannot name a group: give an identifier not starting "
                "with '_', such as 'bees'"
            )
        if hasattr(KitRobot, name) or name in KitRobot.__annotations__:
            raise ValueError(
                f"boards: {name!r} is already the robot's own (robot.{name}): choose another name"
            )
        if not (isinstance(board, type) and issubclass(board, Board)):
            raise TypeError(f"boards: {name!r} must name a Board subclass, not {board!r}")
        checked[name] = board
    return checked
