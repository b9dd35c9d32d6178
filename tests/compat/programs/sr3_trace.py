"""An sr-robot3 program that asks for TRACE logging: the boards' wire traffic is shown."""

from sr.robot3 import Robot

robot = Robot(trace_logging=True, wait_for_start=False)
robot.motor_board.motors[0].power = 0.5
