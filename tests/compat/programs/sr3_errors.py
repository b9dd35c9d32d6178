"""An sr-robot3 program's mistakes get sr-robot3's errors, and its except clauses catch them."""

from collections.abc import Callable
from typing import Any

from sr.robot3 import (
    INPUT,
    OUT_H0,
    OUTPUT,
    BoardDisconnectionError,
    MetadataNotReadyError,
    Robot,
)
from sr.robot3.power_board import BRAIN_OUTPUT


def attempt(what: str, action: Callable[[], Any]) -> None:
    try:
        action()
    except Exception as error:
        print(what, type(error).__name__, error)
    else:
        print(what, "worked")


robot = Robot(wait_for_start=False)
motor = robot.motor_board.motors[0]
servo = robot.servo_board.servos[0]
pins = robot.arduino.pins
attempt("zone before start", lambda: robot.zone)
print("metadata error is a RuntimeError", issubclass(MetadataNotReadyError, RuntimeError))
print("disconnection is an OSError", issubclass(BoardDisconnectionError, OSError))
attempt("power too high", lambda: setattr(motor, "power", 1.5))
attempt("power not a number", lambda: setattr(motor, "power", "fast"))
attempt("servo too far", lambda: setattr(servo, "position", -1.01))
attempt("duty limits", lambda: servo.set_duty_limits(100, 2000))
attempt("duty limit types", lambda: servo.set_duty_limits(1000.0, 2000))
brain = robot.power_board.outputs[BRAIN_OUTPUT]
attempt("brain output", lambda: setattr(brain, "is_enabled", False))
attempt("buzz too high", lambda: robot.power_board.piezo.buzz(20000, 1))
attempt("buzz negative", lambda: robot.power_board.piezo.buzz(440, -1))
attempt("write to input", lambda: pins[5].digital_write(True))
attempt("analogue on digital pin", lambda: pins[5].analog_read())
pins[15].mode = OUTPUT
attempt("analogue on output", lambda: pins[15].analog_read())
pins[15].mode = INPUT
attempt("serial pin read", lambda: pins[0].digital_read())
attempt("serial pin mode", lambda: pins[1].mode)
attempt("mode not a mode", lambda: setattr(pins[5], "mode", "INPUT"))
attempt("bad pulse pin", lambda: robot.arduino.ultrasound_measure(1, 5))
attempt("bad echo pin", lambda: robot.arduino.ultrasound_measure(5, 20))
attempt("two robots", lambda: Robot(wait_for_start=False))
attempt("subclass", lambda: type("MyRobot", (Robot,), {}))
robot.power_board.outputs[OUT_H0].is_enabled = True
print("done")
