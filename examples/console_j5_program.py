"""A j5 program, unchanged but for its import lines, on the console boards.

Run it and answer the start button prompt (or pipe the answer in)::

    echo true | python examples/console_j5_program.py

The console is the point here: it shows, line by line, what each board would be told.

Only ``from j5 import ...`` became ``from j5aio.sync import ...``; the boards and
backends come from ``j5aio.boards`` and ``j5aio.backends``.
"""

from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
)
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import BaseRobot, BoardGroup


class MyRobot(BaseRobot):
    def __init__(self) -> None:
        self._power_boards = BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend)
        self.power_board = self._power_boards.singular()
        self.motor_boards = BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)


r = MyRobot()
print(f"Found Power Board: {r.power_board.serial_number}")
print(f"Power Board Firmware: {r.power_board.firmware_version}")
r.power_board.wait_for_start_flash()
print(f"Found {len(r.motor_boards)} Motor Board(s):")
for board in r.motor_boards:
    print(f" - {board.serial_number} - Version {board.firmware_version}")
for output in r.power_board.outputs:
    output.is_enabled = False
big_led = r.power_board.outputs[0]
big_led.is_enabled = True
r.motor_boards[board.serial_number].motors[0].power = 0.5
r.power_board.piezo.buzz(0.25, 440)
r.motor_boards[board.serial_number].make_safe()
