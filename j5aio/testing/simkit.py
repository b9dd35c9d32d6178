"""A simulated kit opened for a test: simulators, environment and set-up boards together.

:func:`open_simulated_kit` makes a fresh :class:`~j5aio.simulator.kit.SimulatedKit`,
makes it the current kit, finds and sets up every board of it through the simulated
environment, and on leaving closes those boards (which unregisters them) and puts the
previous kit back::

    async with open_simulated_kit(KitConfig(motor_boards=1)) as sim:
        motor = sim.group(MotorBoard)[0].motors[0]
        await motor.set_power(0.5)
        print(sim.kit.motor_boards[0].motors[0])    # what the simulated board does

The ``j5aio_sim_kit`` fixture of the pytest plugin does the same around a test.
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Mapping
from contextlib import asynccontextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar, cast

from j5aio.backends.environment import Environment
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup

if TYPE_CHECKING:
    from j5aio.board_kinds import KitDefinition
    from j5aio.simulator.kit import KitConfig, SimulatedKit

__all__ = ["OpenSimulatedKit", "open_simulated_kit", "simulated_environment"]

BoardT = TypeVar("BoardT", bound=Board)


def simulated_environment() -> Environment:
    """The environment whose backends reach the boards of the current simulated kit."""
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    return SIMULATED_ENVIRONMENT


@dataclass(frozen=True)
class OpenSimulatedKit:
    """A simulated kit in use, with its boards found and set up.

    :param kit: the simulators: look at them to see what the boards did, or change them
        (press a button, put a voltage on a pin) to give the robot inputs.
    :param environment: the environment the boards were found through.
    :param groups: the board group of each kind of board the environment supports.
    """

    kit: SimulatedKit
    environment: Environment
    groups: Mapping[type[Board], BoardGroup[Any]]

    def group(self, board_type: type[BoardT]) -> BoardGroup[BoardT]:
        """Return the group of every ``board_type`` board of the kit.

        :raises KeyError: the environment has no backend for ``board_type``.
        """
        try:
            return cast(BoardGroup[BoardT], self.groups[board_type])
        except KeyError:
            known = ", ".join(sorted(board.__name__ for board in self.groups)) or "none"
            raise KeyError(
                f"the simulated kit has no {board_type.__name__} group; it has: {known}",
            ) from None

    @property
    def boards(self) -> list[Board]:
        """Every board of the kit, as the robot sees them."""
        return [board for group in self.groups.values() for board in group]


@asynccontextmanager
async def open_simulated_kit(
    config: KitConfig | KitDefinition | str | None = None,
    *,
    environment: Environment | None = None,
) -> AsyncIterator[OpenSimulatedKit]:
    """Use a fresh simulated kit, with every board found and set up, then close them all.

    :param config: the kit: its boards (a configuration), a registered kit or its name;
        the default kit if omitted.
    :param environment: the environment to find the boards through; the simulated
        environment if omitted.
    """
    from j5aio.simulator.kit import current_kit, use_kit

    previous = current_kit()
    kit = use_kit(config)
    env = environment if environment is not None else simulated_environment()
    groups: dict[type[Board], BoardGroup[Any]] = {}
    try:
        for board_type in sorted(env.supported_boards, key=lambda board: board.__name__):
            groups[board_type] = await env.get_board_group(board_type)
        yield OpenSimulatedKit(kit=kit, environment=env, groups=groups)
    finally:
        try:
            for group in groups.values():
                for board in group:
                    await board.close()
        finally:
            use_kit(previous)
