"""An sr-robot3 program on the 2019 kit's boards, and the rarer parts of sr-robot3's API."""

import logging
import sys

from sr.robot3 import (
    LED_B,
    OUT_H0,
    Colour,
    MetadataKeyError,
    Note,
    RawSerialDevice,
    Robot,
    list_ports,
)

robot = Robot(
    debug=True, wait_for_start=False, ignored_arduinos=["SIMRG1"],
    manual_boards={"PBv4B": ["/dev/ttyUSB9"]}, raw_ports=[RawSerialDevice("X1")],
)
print("debug", logging.getLogger().level == logging.DEBUG)
print("arduinos", sorted(robot.arduinos))
print("raw", dict(robot.raw_serial_devices))
board = robot.power_board
print("outputs", len(board.outputs), board.outputs[OUT_H0].overcurrent)
board.outputs.power_off()
print("off", [board.outputs[i].is_enabled for i in range(len(board.outputs))])
board.outputs.power_on()
board._run_led.flash()
board._error_led.on()
board._error_led.off()
board.piezo.buzz(Note.A7, 0)  # an empty note: nothing to play
board.piezo.buzz(Note.A7, 0.01)
motor = robot.motor_board.motors[0]
motor.power = 0.25
print("motor reads", motor.power, motor.current, motor.in_fault)
robot.motor_board.reset()
print("reset", motor.power == -1024)
robot.servo_board.servos[0].position = -1
try:
    robot.servo_board.reset()
except OSError as error:
    print("servo reset", error)
print("servo position", robot.servo_board.servos[0].position)
for what in ("power status", "servo status", "servo current"):
    try:
        if what == "power status":
            print(board.status)
        elif what == "servo status":
            print(robot.servo_board.status())
        else:
            print(robot.servo_board.current)
    except OSError as error:
        print(what, type(error).__name__)
print("motor status", robot.motor_board.status)
robot.kch.leds[LED_B].colour = Colour.GREEN
robot.kch.leds[LED_B].g = True
print("kch", robot.kch.leds[LED_B].colour, robot.kch.leds[LED_B].r)
try:
    robot.kch.leds[LED_B].colour = (True, False)
except ValueError as error:
    print("colour", error)
print("key error", MetadataKeyError("zone"))
arduino = robot.arduino
try:
    arduino.command("v")
except OSError as error:
    print("command", type(error).__name__)
try:
    arduino.ultrasound_measure(4, 5)
except OSError as error:
    print("ultrasound", type(error).__name__)
print("reprs", repr(board).startswith("<PowerBoard"), repr(motor).startswith("<Motor index=0"),
      repr(arduino.pins[2]))
print("time", robot.time() > 1.7e9)
robot.wait_start()
robot.wait_start()  # a second start, as sr-robot3 allows
print("started twice", robot.zone)
list_ports()
sys.exit(0)
