"""An sr-robot3 program whose motor board's cable is pulled out (by the test) mid-run."""

from typing import Any

from sr.robot3 import BoardDisconnectionError, Robot

from j5aio.simulator.kit import current_kit

robot = Robot(wait_for_start=False)
robot.motor_board.motors[0].power = 0.5
motor_board_simulator: Any = current_kit().simulators("sr-motor-fw4")[0]
motor_board_simulator.unplug()  # (the test pulls the cable)
try:
    robot.motor_board.motors[0].power = 0.25
except BoardDisconnectionError as error:
    print("caught", isinstance(error, OSError), type(error.__cause__).__module__)
print("still running", robot.power_board.battery_sensor.voltage > 0)
