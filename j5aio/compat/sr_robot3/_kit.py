"""The kit an sr-robot3 ``Robot`` is built on: j5aio's KitRobot, through the sync facade.

One difference from KitRobot: sr-robot3's ``no_powerboard=True`` runs a robot that has
no power board, where KitRobot needs exactly one.
"""

from __future__ import annotations

from j5aio.errors import CommunicationError
from j5aio.kit import KitRobot as CoreKitRobot
from j5aio.sync import KitRobot
from j5aio.sync.wrapping import adopt, call

__all__ = ["CompatKitRobot", "open_kit"]


class CompatKitRobot(CoreKitRobot):
    """KitRobot that may go without a power board.

    :param power_board_needed: ``False`` for sr-robot3's ``no_powerboard=True``.
    """

    def __init__(self, *, power_board_needed: bool = True) -> None:
        super().__init__()
        self._power_board_needed = power_board_needed

    async def setup(self) -> None:
        """Find every board of the kit, and the power board unless it is not needed.

        :raises CommunicationError: as :meth:`j5aio.kit.KitRobot.setup`; without a power
            board only if one is needed.
        """
        try:
            await super().setup()
        except CommunicationError:
            if self._power_board_needed or not hasattr(self, "kch"):
                raise  # (also: it failed before every group was looked for)


def open_kit(*, power_board_needed: bool = True) -> KitRobot:
    """Make the kit robot and find its boards, as ``j5aio.sync.KitRobot()`` does.

    :raises UnableToObtainLock: another robot is running.
    :raises CommunicationError: a board could not be reached, or (when it is needed)
        there is not exactly one power board.
    """
    core = CompatKitRobot(power_board_needed=power_board_needed)
    robot = adopt(KitRobot, core)
    try:
        call(core.setup)
    except BaseException:
        core.release_lock()
        raise
    return robot
