"""Drive a zig-zag with the Arduino's LED (pin 13) lit while driving straight.

Run it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/sync_blink_and_drive.py

The student tutorial's picture of the kit in action is a recording of this program
(``python tools/plot_kit_run.py``).
"""

import time

from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.sync import KitRobot

robot = KitRobot()
left, right = robot.motor_boards[0].motors
led = robot.arduinos[0].pins[13]
led.mode = GPIOPinMode.DIGITAL_OUTPUT

for _ in range(2):
    led.digital_write(True)  # straight on, LED lit
    left.power = 0.6
    right.power = 0.6
    time.sleep(0.5)
    led.digital_write(False)  # turn, LED dark
    left.power = 0.5
    right.power = -0.5
    time.sleep(0.3)

left.power = MotorSpecialState.BRAKE
right.power = MotorSpecialState.BRAKE
print("Zig-zag done: both motors braked.")
