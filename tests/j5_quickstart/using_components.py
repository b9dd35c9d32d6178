# j5's quick start, step 3 ("using components"), with only the imports changed.
from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.sync import BaseRobot, BoardGroup


class MyRobot(BaseRobot):
    """A power board, and its first output given a name."""

    def __init__(self) -> None:
        self._power_boards = BoardGroup.get_board_group(
            PowerBoard,
            SRV4PowerBoardConsoleBackend,
        )
        self.power_board = self._power_boards.singular()
        self.big_led = self.power_board.outputs[0]


r = MyRobot()

for output in r.power_board.outputs:
    output.is_enabled = False

r.big_led.is_enabled = True
