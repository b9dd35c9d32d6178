"""Blink the power board's run LED three times.

Run it on the console boards::

    python examples/sync_blink_run_led.py
"""

import time

from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.sync import BoardGroup

power_board = BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend).singular()

for _ in range(3):
    power_board.run_led.state = True
    time.sleep(0.2)
    power_board.run_led.state = False
    time.sleep(0.2)

print(f"The run LED is {'on' if power_board.run_led.state else 'off'}.")
