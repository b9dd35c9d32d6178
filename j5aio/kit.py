"""KitRobot: a ready-made robot for the Student Robotics v4 and SourceBots kit.

::

    from j5aio.kit import KitRobot

    async with KitRobot() as robot:
        await robot.motor_boards[0].motors[0].set_power(0.5)
        volts = await robot.power_board.battery_sensor.get_voltage()

Its boards are found through the environment passed in, or else the default one (real
hardware, unless ``J5AIO_ENV`` or ``python -m j5aio run --sim`` chose otherwise: see
:mod:`j5aio.environments`).
"""

from __future__ import annotations

from j5aio.backends.environment import Environment
from j5aio.boards.board_group import BoardGroup
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard
from j5aio.environments import get_default_environment, hint_no_hardware
from j5aio.robot import BaseRobot

__all__ = ["KitRobot"]


class KitRobot(BaseRobot):
    """A robot built from an SR v4 power board and any SR v4 / SourceBots boards beside it.

    After ``async with KitRobot() as robot`` it has:

    - ``robot.power_board``: the one power board (an error says so if there is not
      exactly one);
    - ``robot.motor_boards``, ``robot.servo_boards``, ``robot.arduinos`` (SourceBots
      Arduinos) and ``robot.ruggeduinos``: groups of every such board found, possibly
      empty, reached by position or serial number.

    Through :mod:`j5aio.sync` (``from j5aio.sync import KitRobot``), ``robot = KitRobot()``
    finds the boards at once, with no ``async with``, and they are made safe when the
    program ends.

    :param environment: where to find the boards; the default environment if omitted.
    :raises TypeError: ``environment`` is not an Environment.
    """

    power_board: PowerBoard
    power_boards: BoardGroup[PowerBoard]
    motor_boards: BoardGroup[MotorBoard]
    servo_boards: BoardGroup[ServoBoard]
    arduinos: BoardGroup[SBArduinoBoard]
    ruggeduinos: BoardGroup[Ruggeduino]

    def __init__(self, *, environment: Environment | None = None) -> None:
        if environment is not None and not isinstance(environment, Environment):
            self.release_lock()
            raise TypeError(
                f"environment must be an Environment (such as SIMULATED_ENVIRONMENT), "
                f"not {type(environment).__name__}"
            )
        super().__init__()
        self._environment = environment
        self._chosen_by_default = environment is None

    @property
    def environment(self) -> Environment:
        """The environment the boards are found in."""
        if self._environment is None:
            self._environment = get_default_environment()
        return self._environment

    async def setup(self) -> None:
        """Find every board of the kit, then the power board.

        :raises CommunicationError: there is not exactly one power board, or a board
            could not be reached. When the hardware was looked at only by default and
            nothing was found (or it could not be looked at), one line says how to run
            on the simulated kit instead.
        """
        environment = self.environment
        self.power_boards = await environment.get_board_group(PowerBoard)
        self.motor_boards = await environment.get_board_group(MotorBoard)
        self.servo_boards = await environment.get_board_group(ServoBoard)
        self.arduinos = await environment.get_board_group(SBArduinoBoard)
        self.ruggeduinos = await environment.get_board_group(Ruggeduino)
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
