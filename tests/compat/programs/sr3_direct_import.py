"""A program written for j5aio that uses sr-robot3's API by j5aio's own module name."""

from j5aio.compat.sr_robot3 import OUT_L0, Robot

robot = Robot(wait_for_start=False)
robot.power_board.outputs[OUT_L0].is_enabled = False
robot.motor_board.motors[1].power = 0.75
print("direct", robot.motor_board.motors[1].power, robot.power_board.outputs[OUT_L0].is_enabled)
