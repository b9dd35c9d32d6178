"""A short sr-robot3 program, run once by sr-robot3 itself and once by j5aio's sr-robot3.

``WIRE_BOARDS`` (JSON) gives sr-robot3 the serial ports of the simulated boards; j5aio
finds them itself. Each board is first asked one reading, a marker the wire test lines the
two runs up by (what comes before it is how each finds its boards).
"""

import json
import os

from sr.robot3 import A0, A5, BRAKE, COAST, INPUT_PULLUP, OUT_H1, OUTPUT, Note, Robot

robot = Robot(
    wait_for_start=False, manual_boards=json.loads(os.environ.get("WIRE_BOARDS", "{}")),
)
power, motors, servos = robot.power_board, robot.motor_board.motors, robot.servo_board.servos
arduino = robot.arduino
# the markers
print("marks", power.battery_sensor.voltage, motors[0].current, robot.servo_board.voltage,
      arduino.pins[A5].analog_read())

motors[0].power = 0.5
motors[1].power = -0.3337
print("motors", motors[0].power, motors[1].power)
motors[0].power = BRAKE
motors[1].power = COAST
servos[0].position = 0.25
servos[1].set_duty_limits(1200, 1800)
servos[1].position = -0.5
servos[2].position = None
print("servos", servos[0].position, servos[1].position)
power.outputs[OUT_H1].is_enabled = False
print("h1", power.outputs[OUT_H1].is_enabled, power.outputs[OUT_H1].current)
power.outputs[OUT_H1].is_enabled = True
power.piezo.buzz(Note.E7, 0.123)
power.piezo.buzz(523.9, 1.5)
arduino.pins[3].mode = INPUT_PULLUP
arduino.pins[7].mode = OUTPUT
arduino.pins[7].digital_write(True)
print("pins", arduino.pins[3].digital_read(), arduino.pins[A0].analog_read())
arduino.pins[7].digital_write(False)
print("distance", arduino.ultrasound_measure(4, 5))
