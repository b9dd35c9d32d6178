"""An sr-robot3 program in a match: zone, arena and mode after the start, until game over."""

from sr.robot3 import COMP, Robot

robot = Robot()
print("start", robot.zone, robot.arena, robot.mode, robot.mode == COMP, robot.is_simulated)
print("usbkey", robot.usbkey.is_dir())
start = robot.time()
while True:  # the match timer ends the program
    robot.motor_board.motors[0].power = 0.3
    robot.sleep(0.05)
    if robot.time() - start > 30:
        print("the match timer did not end the program")
        break
