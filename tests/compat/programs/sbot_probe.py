"""An sbot program that tries every call, the wrong ways too, and prints what happened."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

import json
import os
import shutil
import sys
import tempfile
from collections.abc import Callable

import sbot
from sbot import AnalogPin, Colour, GPIOPinMode, arduino, leds, motors, power, servos, utils, vision

from j5aio.competition import start

results: dict[str, object] = {}


def attempt(name: str, call: Callable[[], object]) -> None:
    """Run ``call``; record its result, or the kind of error and its message."""
    try:
        value = call()
    except Exception as error:
        results[name] = [type(error).__name__, str(error)]
    else:
        results[name] = value


attempt("too_fast", lambda: motors.set_power(0, 2))
attempt("no_motor", lambda: motors.set_power(5, 0.1))
attempt("negative_motor", lambda: motors.set_power(-1, 0.1))
attempt("word_power", lambda: motors.set_power(0, "fast"))
attempt("motor_status", lambda: list(motors.status(1)))
attempt("in_fault", lambda: motors.in_fault(1))
motors.set_power(0, 0.3)
motors.reset()
attempt("after_reset", lambda: [motors.get_power(0), motors.get_power(1)])

attempt("brain", lambda: power.set_output(4, False))
attempt("no_output", lambda: power.set_output(9, True))
attempt("output_word", lambda: power.is_output_on("H0"))
power.set_output(sbot.PowerOutputPosition.H1, False)
attempt("h1", lambda: power.is_output_on(1))
attempt("h0_current", lambda: power.get_output_current(0))
attempt("power_status", lambda: list(power.status())[:4])

attempt("low_limit", lambda: servos.set_duty_limits(0, 100, 2000))
attempt("float_limit", lambda: servos.set_duty_limits(0, 1.5, 2000))
attempt("no_servo", lambda: servos.set_position(8, 0))
attempt("far_servo", lambda: servos.set_position(0, 1.5))
servos.set_duty_limits(3, 2000, 1000)
servos.set_position(3, 0.25)
attempt("reversed", lambda: [servos.get_duty_limits(3), servos.get_position(3)])
servos.set_duty_limits(4, 1500, 1500)
servos.set_position(4, -1)
attempt("equal", lambda: servos.get_duty_limits(4))
servos.set_position(5, 1)
servos.disable(5)
attempt("disabled", lambda: servos.get_position(5))
attempt("servo_status", lambda: list(servos.status(0)))
attempt("servo_rail", lambda: [servos.get_current(0), servos.get_voltage(0)])

attempt("serial_pin", lambda: arduino.set_pin_mode(0, GPIOPinMode.INPUT))
attempt("no_pin", lambda: arduino.digital_read(25))
attempt("mode_word", lambda: arduino.set_pin_mode(3, "INPUT"))
attempt("digital_analog", lambda: arduino.analog_read(3))
arduino.set_pin_mode(AnalogPin.A2, GPIOPinMode.INPUT_PULLUP)
attempt("pulled_analog", lambda: arduino.analog_read(AnalogPin.A2))
arduino.set_pin_mode(AnalogPin.A3, GPIOPinMode.OUTPUT)
attempt("output_analog", lambda: arduino.analog_read(AnalogPin.A3))
arduino.set_pin_mode(6, GPIOPinMode.OUTPUT)
arduino.digital_write(6, True)
attempt("read_output", lambda: arduino.digital_read(6))
arduino.set_pin_mode(7, GPIOPinMode.INPUT)
arduino.digital_write(7, True)  # an input's pull-up, as the firmware does
arduino.set_pin_mode(10, GPIOPinMode.INPUT_PULLUP)
arduino.digital_write(10, False)
attempt("a1_digital_then_analog", lambda: [
    arduino.digital_read(AnalogPin.A1), arduino.analog_read(AnalogPin.A1),
])
arduino.set_pin_mode(11, GPIOPinMode.INPUT)
arduino.set_pin_mode(11, GPIOPinMode.INPUT)
attempt("bad_pulse_pin", lambda: arduino.measure_ultrasound_distance(1, 9))
attempt("bad_echo_pin", lambda: arduino.measure_ultrasound_distance(8, 30))
attempt("no_echo", lambda: arduino.measure_ultrasound_distance(11, 12))

leds.set_colour(1, Colour.MAGENTA)
attempt("led", lambda: leds.get_colour(1).name)
attempt("no_led", lambda: leds.set_colour(3, Colour.RED))

folder = tempfile.mkdtemp()
frame = vision.capture(save=os.path.join(folder, "raw"))
seen = vision.detect_markers(save=os.path.join(folder, "seen.png"))
again = vision.detect_markers(frame=frame)
results["vision"] = {
    "shape": list(frame.shape),
    "files": sorted(os.listdir(folder)),
    "ids": [marker.id for marker in seen],
    "same": [marker.id for marker in again] == [marker.id for marker in seen],
    "sizes": sorted({marker.size for marker in seen}),
    "distance_is_int": all(isinstance(m.position.distance, int) for m in seen),
    "repr": repr(seen[0]) if seen else "",
}
shutil.rmtree(folder)

attempt("negative_sleep", lambda: utils.sleep(-1))
attempt("low_note", lambda: utils.sound_buzzer(5, 1))
attempt("long_note", lambda: utils.sound_buzzer(440, 1e9))
attempt("reload", utils.load_boards)
start.trigger_start()  # (what the start button would do)
attempt("restart", utils.wait_start)
results["reprs"] = [repr(motors), repr(servos), repr(power), repr(arduino)]
power.reset()
attempt("after_power_reset", lambda: power.is_output_on(0))
servos.reset()

print("RESULT " + json.dumps(results), flush=True)
sys.exit(0)
