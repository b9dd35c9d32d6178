"""One program for every kit: real boards, the simulated kit, or the console.

``J5AIO_ENV`` chooses where the boards are (hardware when it is unset)::

    J5AIO_ENV=sim python examples/sync_any_kit.py
    printf '12.2\n' | J5AIO_ENV=console python examples/sync_any_kit.py
"""

import time

from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import get_default_environment

environment = get_default_environment()
print(f"Using the {environment.name}.")

power_board = environment.get_board_group(PowerBoard).singular()
# The motor board takes its 12 V from the power board's outputs, which are off when the
# power board starts: switch them on, and give the motor board a moment to boot, before
# looking for it (KitRobot does this for you).
power_board.outputs.power_on()
time.sleep(0.5)
motor_board = environment.get_board_group(MotorBoard)[0]

power_board.run_led.state = True
print(f"Battery: {power_board.battery_sensor.voltage:.1f} V")

motor_board.motors[0].power = 0.5
motor_board.motors[1].power = 0.5
motor_board.make_safe()
print(f"Motors: {motor_board.motors[0].power}, {motor_board.motors[1].power}")
