"""Blink the power board's run LED three times.

Run it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/sync_blink_run_led.py
    python -m j5aio run examples/sync_blink_run_led.py
"""

import time

from j5aio.sync import KitRobot

robot = KitRobot()
run_led = robot.power_board.run_led

for _ in range(3):
    run_led.state = True
    time.sleep(0.2)
    run_led.state = False
    time.sleep(0.2)

print(f"The run LED is {'on' if run_led.state else 'off'}.")
