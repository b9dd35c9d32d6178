# j5's quick start, step 2 ("adding boards"), with only the imports changed.
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
)
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import BaseRobot, BoardGroup


class MyRobot(BaseRobot):
    """A power board and any number of motor boards."""

    def __init__(self) -> None:
        self._power_boards = BoardGroup.get_board_group(
            PowerBoard,
            SRV4PowerBoardConsoleBackend,
        )
        self.power_board = self._power_boards.singular()

        self.motor_boards = BoardGroup.get_board_group(
            MotorBoard,
            SRV4MotorBoardConsoleBackend,
        )


r = MyRobot()

print(f"Found Power Board: {r.power_board.serial_number}")
print(f"Power Board Firmware: {r.power_board.firmware_version}")

r.power_board.wait_for_start_flash()

print(f"Found {len(r.motor_boards)} Motor Board(s):")

for board in r.motor_boards:
    print(f" - {board.serial_number} - Version {board.firmware_version}")

r.motor_boards["218312"].make_safe()
