"""sr-robot3's documented uses, one after another (Student Robotics' programming docs)."""

import math

from sr.robot3 import (
    A0,
    COAST,
    INPUT,
    LED_A,
    OUT_FIVE_VOLT,
    OUT_H0,
    OUTPUT,
    Colour,
    Note,
    Robot,
)

robot = Robot(wait_for_start=False)
robot.wait_start()

# Motors: by the serial number the start-up log printed, or the one board.
serial = next(iter(robot.motor_boards))
robot.motor_boards[serial].motors[0].power = 1
robot.motor_boards[serial].motors[1].power = -1
robot.motor_board.motors[1].power = 0.5
robot.sleep(0.1)
robot.motor_board.motors[0].power = COAST
print("tour motors", robot.motor_board.motors[1].power)

# Power board: outputs, buzzer, battery.
robot.power_board.outputs[OUT_H0].is_enabled = False
robot.power_board.outputs[OUT_FIVE_VOLT].is_enabled = True
robot.power_board.piezo.buzz(1000, 0.5)
robot.power_board.piezo.buzz(Note.D7, 0.25)
print("tour battery", robot.power_board.battery_sensor.voltage > 10)

# Servos and the Arduino.
robot.servo_board.servos[0].position = -0.5
robot.arduino.pins[3].mode = OUTPUT
robot.arduino.pins[3].digital_write(True)
robot.arduino.pins[A0].mode = INPUT
print("tour arduino", 0 <= robot.arduino.pins[A0].analog_read() <= 5,
      robot.arduino.ultrasound_measure(4, 5) >= 0)

# Vision: every marker seen, its distance in mm and angles in radians.
for marker in robot.camera.see():
    angle = math.degrees(marker.position.horizontal_angle)
    if marker.position.distance <= 0 or abs(angle) > 90:
        print("tour marker out of view", marker)
print("tour vision", len(robot.camera.see()) > 0)

# The KCH's LEDs and the match's metadata.
robot.kch.leds[LED_A].colour = Colour.YELLOW
print("tour metadata", robot.zone, robot.arena, robot.mode)
