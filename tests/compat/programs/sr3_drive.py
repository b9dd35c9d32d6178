"""An sr-robot3 program as a team writes it: drive, steer a servo, signal, read the battery."""

from sr.robot3 import BRAKE, COAST, OUT_H0, OUT_L1, Note, Robot

robot = Robot()

motors = robot.motor_board.motors
motors[0].power = 0.5
motors[1].power = -0.25
print("powers", motors[0].power, motors[1].power)
robot.sleep(0.05)
motors[0].power = 0.1234  # sent in thousandths, truncated: 123
motors[1].power = BRAKE
print("braked", motors[1].power)
motors[1].power = COAST
print("coasting", motors[1].power == COAST)

servo = robot.servo_board.servos[2]
servo.position = 0.5
print("servo", servo.position)
servo.set_duty_limits(2000, 1000)  # turned round
servo.position = 0.5
print("reversed", servo.position, servo.get_duty_limits())
robot.servo_board.servos[3].position = None
print("off", robot.servo_board.servos[3].position)

board = robot.power_board
print("outputs on", [board.outputs[i].is_enabled for i in range(7)])
board.outputs[OUT_L1].is_enabled = False
print("L1", board.outputs[OUT_L1].is_enabled, "H0 current", board.outputs[OUT_H0].current)
print("battery", board.battery_sensor.voltage > 0, board.battery_sensor.current >= 0)
board.piezo.buzz(Note.C6, 0.25)
board.piezo.buzz(440.7, 0.0119)  # whole hertz and milliseconds, truncated
board.piezo.buzz(1000, 0.05, blocking=True)
print("identity", list(board.identify())[:2], list(robot.motor_board.identify())[:2])
print("serials", sorted(robot.motor_boards), sorted(robot.servo_boards))
