"""Read the battery's voltage and current, and warn when it is running low.

Run it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/sync_read_battery.py
"""

from j5aio.sync import KitRobot

LOW_VOLTS = 11.0

robot = KitRobot()
battery = robot.power_board.battery_sensor

volts = battery.voltage
amps = battery.current
print(f"Battery: {volts:.2f} V, drawing {amps:.2f} A ({volts * amps:.1f} W).")
if volts < LOW_VOLTS:
    print("The battery is low: charge it soon!")
