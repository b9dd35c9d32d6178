"""Every board of an sr-robot3 program unplugged (by the test): each call fails as sr-robot3's."""

from collections.abc import Callable
from typing import Any

from sr.robot3 import A0, OUTPUT, BoardDisconnectionError, Robot

from j5aio.simulator.kit import current_kit

robot = Robot(wait_for_start=False)
power, motor_board, servo_board = robot.power_board, robot.motor_board, robot.servo_board
motor, servo, arduino = motor_board.motors[0], servo_board.servos[0], robot.arduino
arduino.pins[7].mode = OUTPUT
print("reprs", " ".join(repr(thing).split(" ")[0] for thing in (
    power.outputs, power.outputs[0], power._run_led, power.battery_sensor, power.piezo,
    motor_board, motor, servo_board, servo, arduino, arduino.pins[7], robot.camera)))
print("types", motor_board.get_board_type(), servo_board.get_board_type(),
      arduino.get_board_type(), robot.camera.get_board_type(), power.get_board_type())
print("status", power.status.temperature, servo_board.status().power_good,
      servo_board.current >= 0, motor.in_fault)
robot.camera.close()
kit: Any = current_kit()
for name in ("sr-power-fw4", "sr-motor-fw4", "sr-servo-fw4", "sr-arduino-fw2"):
    for simulator in kit.simulators(name):
        simulator.unplug()  # (the test pulls every cable)


def setter(thing: object, name: str, value: object) -> Callable[[], None]:
    return lambda: setattr(thing, name, value)


calls: dict[str, Callable[[], Any]] = {
    "output get": lambda: power.outputs[0].is_enabled,
    "output set": setter(power.outputs[0], "is_enabled", False),
    "output current": lambda: power.outputs[0].current,
    "output overcurrent": lambda: power.outputs[0].overcurrent,
    "led": power._run_led.on,
    "battery voltage": lambda: power.battery_sensor.voltage,
    "battery current": lambda: power.battery_sensor.current,
    "buzz": lambda: power.piezo.buzz(440, 0.1),
    "power status": lambda: power.status,
    "power reset": power.reset,
    "start button": power._start_button,
    "motor get": lambda: motor.power,
    "motor set": setter(motor, "power", 0.5),
    "motor current": lambda: motor.current,
    "motor fault": lambda: motor.in_fault,
    "motor status": lambda: motor_board.status,
    "servo get": lambda: servo.position,
    "servo set": setter(servo, "position", 0.5),
    "servo off": servo.disable,
    "servo limits": lambda: servo.set_duty_limits(1100, 1900),
    "servo status": servo_board.status,
    "servo current": lambda: servo_board.current,
    "servo voltage": lambda: servo_board.voltage,
    "pin mode": setter(arduino.pins[3], "mode", OUTPUT),
    "digital read": arduino.pins[4].digital_read,
    "digital write": lambda: arduino.pins[7].digital_write(True),
    "analog read": arduino.pins[A0].analog_read,
    "command": lambda: arduino.command("v"),
    "ultrasound": lambda: arduino.ultrasound_measure(4, 5),
}
failed = []
for name, call in calls.items():
    try:
        call()
    except BoardDisconnectionError:
        failed.append(name)
print("failed", len(failed), "of", len(calls))
print("worked", sorted(set(calls) - set(failed)))
