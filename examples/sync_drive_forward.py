"""Drive forwards for half a second, then brake.

Run it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/sync_drive_forward.py
"""

import time

from j5aio.components.motor import MotorSpecialState
from j5aio.sync import KitRobot

robot = KitRobot()
left, right = robot.motor_boards[0].motors

left.power = 0.6
right.power = 0.6
time.sleep(0.5)

left.power = MotorSpecialState.BRAKE
right.power = MotorSpecialState.BRAKE
print(f"Stopped: left is {left.power}, right is {right.power}.")
