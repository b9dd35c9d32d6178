"""Drive forwards for half a second, then brake.

Run it on the console boards::

    python examples/sync_drive_forward.py
"""

import time

from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.components.motor import MotorSpecialState
from j5aio.sync import BoardGroup

motor_board = BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend).singular()
left, right = motor_board.motors

left.power = 0.6
right.power = 0.6
time.sleep(0.5)

left.power = MotorSpecialState.BRAKE
right.power = MotorSpecialState.BRAKE
print(f"Stopped: left is {left.power}, right is {right.power}.")
