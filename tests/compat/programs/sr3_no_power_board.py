"""An sr-robot3 program for a robot without a power board."""

from sr.robot3 import Robot

robot = Robot(no_powerboard=True)
try:
    print(robot.power_board)
except RuntimeError as error:
    print("power board", error)
robot.motor_board.motors[0].power = -0.5
print("motor", robot.motor_board.motors[0].power, robot.mode)
