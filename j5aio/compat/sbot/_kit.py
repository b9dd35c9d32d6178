"""The kit behind sbot's modules: j5aio's KitRobot, and sbot's numbering of its outputs.

sbot's modules (``motors``, ``servos``, ``power``, ``arduino``, ``leds``, ``vision``,
``utils``) share one :class:`KitLink`. :meth:`KitLink.load` makes the robot through
j5aio's sync facade (:class:`j5aio.sync.KitRobot`: the boards of whichever environment
the program runs in, real or simulated) and numbers the outputs as sbot does: motors
0 and 1 are the first motor board's (boards in serial-number order, unless the
``SORT_MOTOR_ORDER`` override lists them), 2 and 3 the next board's; servos likewise,
eight to a board.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Final, Generic, NamedTuple, TypeVar, cast

from ._overrides import get_overrides

if TYPE_CHECKING:
    from j5aio.sync import (
        KitRobot,
        MonitoredMotor,
        MotorBoardFw4,
        PowerBoardFw4,
        PulseServo,
        SBArduino2024Board,
        ServoBoardFw4,
    )

__all__ = ["NOT_LOADED", "SBOT_KIT", "KitLink", "Output", "choose_sourcebots_kit"]

LOGGER = logging.getLogger("sbot.internal.board_manager")

#: What sbot says when an output is used before the boards are found.
NOT_LOADED: Final = (
    "Boards cannot be accessed before they are loaded. Run utils.load_boards() first."
)

#: The simulated kit an sbot program gets when the simulator is chosen but no kit is.
SBOT_KIT: Final = "sb2024"

BoardT = TypeVar("BoardT")
ComponentT = TypeVar("ComponentT")


class Output(NamedTuple, Generic[BoardT, ComponentT]):
    """One numbered output: the board it is on, its number there, and its component."""

    board: BoardT
    idx: int
    component: ComponentT


def _sorted_boards(boards: Sequence[BoardT], order: str | None, kind: str) -> list[BoardT]:
    """The boards in serial-number order, or in the order a ``SORT_<KIND>_ORDER`` gives.

    :raises RuntimeError: the order leaves out a board that is present (as sbot).
    """
    by_serial: dict[str, BoardT] = {
        board.serial_number: board  # type: ignore[attr-defined]
        for board in boards
    }
    if not order:
        return [by_serial[serial] for serial in sorted(by_serial)]
    wanted = order.split(",")
    extra = set(by_serial) - set(wanted)
    if extra:
        raise RuntimeError(
            f"Extra boards found for {kind}: {', '.join(sorted(extra))}."
            "Cannot use custom sort order",
        )
    return [by_serial[serial] for serial in wanted if serial in by_serial]


class KitLink:
    """The robot and its numbered outputs, shared by sbot's modules."""

    def __init__(self) -> None:
        self._robot: KitRobot | None = None
        self.motors: list[Output[MotorBoardFw4, MonitoredMotor]] = []
        self.servos: list[Output[ServoBoardFw4, PulseServo]] = []
        self.motor_boards: list[MotorBoardFw4] = []
        self.servo_boards: list[ServoBoardFw4] = []
        self.arduinos: list[SBArduino2024Board] = []

    @property
    def loaded(self) -> bool:
        """Whether :meth:`load` has found the boards."""
        return self._robot is not None

    @property
    def robot(self) -> KitRobot:
        """The robot.

        :raises AssertionError: the boards have not been loaded yet (as sbot).
        """
        if self._robot is None:
            raise AssertionError(NOT_LOADED)
        return self._robot

    def load(self) -> None:
        """Find the boards (j5aio's KitRobot, which powers the kit up) and number outputs.

        :raises RuntimeError: the boards have been loaded already.
        """
        if self._robot is not None:
            raise RuntimeError("Boards have already been loaded")
        from j5aio.sync import KitRobot

        choose_sourcebots_kit()
        # (As sbot, KitRobot switches on every power output but the brain's before it
        # looks for the motor and servo boards, which those outputs feed.)
        robot = KitRobot()
        overrides = get_overrides()
        self.motor_boards = _sorted_boards(
            cast("list[MotorBoardFw4]", list(robot.motor_boards)),
            overrides.get("SORT_MOTOR_ORDER"),
            "motor",
        )
        self.servo_boards = _sorted_boards(
            cast("list[ServoBoardFw4]", list(robot.servo_boards)),
            overrides.get("SORT_SERVO_ORDER"),
            "servo",
        )
        self.motors = [
            Output(board, idx, motor)
            for board in self.motor_boards
            for idx, motor in enumerate(board.motors)
        ]
        for servo_board in self.servo_boards:
            servo_board.unpower_when_safe = True  # (sbot resets the board at exit: servos off)
        self.servos = [
            Output(board, idx, servo)
            for board in self.servo_boards
            for idx, servo in enumerate(board.servos)
        ]
        self.arduinos = _sb2024_arduinos(robot)
        self._robot = robot

    def power_board(self) -> PowerBoardFw4:
        """The power board.

        :raises AssertionError: the boards have not been loaded yet.
        """
        return self.robot.power_board  # type: ignore[return-value]

    def motor(self, id: int) -> Output[MotorBoardFw4, MonitoredMotor]:
        """Motor ``id`` across every motor board (sbot's numbering)."""
        found = self._find(self.motors, id, "motor board")
        return cast("Output[MotorBoardFw4, MonitoredMotor]", found)

    def servo(self, id: int) -> Output[ServoBoardFw4, PulseServo]:
        """Servo ``id`` across every servo board (sbot's numbering)."""
        found = self._find(self.servos, id, "servo board")
        return cast("Output[ServoBoardFw4, PulseServo]", found)

    def arduino(self) -> SBArduino2024Board:
        """The Arduino.

        :raises ValueError: there is none (sbot's message).
        """
        if not self.arduinos:
            self.robot  # noqa: B018 - not loaded is the error to give first
            raise ValueError("No Arduinos connected")
        return self.arduinos[0]

    def _find(self, outputs: list[Any], id: int, name: str) -> Any:
        if not self.loaded:
            raise AssertionError(NOT_LOADED)
        if isinstance(id, bool) or not isinstance(id, int):
            raise TypeError(f"an output number is an int from 0, not {id!r}")
        if id < 0:
            raise AssertionError("Output identifiers must be positive")
        try:
            return outputs[id]
        except IndexError:
            raise ValueError(f"Output {id} does not exist on {name}") from None

    def log_connected_boards(self) -> None:
        """Log the boards found and the numbering of their outputs, as sbot does."""
        robot = self.robot
        LOGGER.info("Connected power board, serial: %s", robot.power_board.serial_number)
        numbered: tuple[tuple[str, Sequence[Output[Any, Any]]], ...] = (
            ("motor board", self.motors), ("servo board", self.servos),
        )
        for name, outputs in numbered:
            if not outputs:
                continue
            boards = {output.board.serial_number for output in outputs}
            LOGGER.info("Connected %d %ss", len(boards), name)
            for index, output in enumerate(outputs):
                LOGGER.info(
                    "Index: %d  =>  serial: %s, output %d",
                    index, output.board.serial_number, output.idx,
                )
        for arduino in self.arduinos:
            LOGGER.info("Connected Arduino, serial: %s", arduino.serial_number)
        if robot.camera is not None:
            LOGGER.info("Connected camera: %s", robot.cameras[0].serial_number)
        else:
            LOGGER.info("No cameras connected")


def choose_sourcebots_kit() -> None:
    """On the simulator with no kit named, make the kit SourceBots' own (``sb2024``).

    An sbot program is written for that kit; a kit named with ``--kit`` or
    ``J5AIO_KIT`` (or already made) is left as it is.
    """
    from j5aio.environments import ENVIRONMENT_VARIABLE
    from j5aio.simulator.kit import KIT_VARIABLE

    if os.environ.get(ENVIRONMENT_VARIABLE) == "sim" and not os.environ.get(KIT_VARIABLE):
        os.environ[KIT_VARIABLE] = SBOT_KIT
        LOGGER.info("Simulated kit: %s (SourceBots' kit)", SBOT_KIT)


def _sb2024_arduinos(robot: KitRobot) -> list[SBArduino2024Board]:
    """The SourceBots Arduinos with the sb2024 firmware among ``robot.arduinos``."""
    from j5aio.sync import SBArduino2024Board

    return [
        board
        for board in cast("list[object]", list(robot.arduinos))
        if isinstance(board, SBArduino2024Board)
    ]
