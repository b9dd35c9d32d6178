"""Read the battery's voltage and current, and warn when it is running low.

Run it and type the readings the console asks for (or pipe them in)::

    printf '11.9\n2.5\n' | python examples/sync_read_battery.py
"""

from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.sync import BoardGroup

LOW_VOLTS = 11.0

power_board = BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend).singular()
battery = power_board.battery_sensor

volts = battery.voltage
amps = battery.current
print(f"Battery: {volts:.2f} V, drawing {amps:.2f} A ({volts * amps:.1f} W).")
if volts < LOW_VOLTS:
    print("The battery is low: charge it soon!")
