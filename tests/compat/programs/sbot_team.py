"""A competition robot as a team writes it with sbot: find a token, drive to it, grab it."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

import math
import time

import sbot
from sbot import AnalogPin, Colour, GPIOPinMode, Note

LEFT, RIGHT = 0, 1
GRABBER = 0
TRIGGER, ECHO = 8, 9

sbot.arduino.set_pin_mode(2, GPIOPinMode.INPUT_PULLUP)  # the bump switch
sbot.arduino.set_pin_mode(AnalogPin.A0, GPIOPinMode.INPUT)  # the reflectance sensor
sbot.servos.set_duty_limits(GRABBER, 500, 2500)
sbot.servos.set_position(GRABBER, -1)  # open


def drive(left: float, right: float) -> None:
    sbot.motors.set_power(LEFT, left)
    sbot.motors.set_power(RIGHT, right)


def stop() -> None:
    drive(sbot.BRAKE, sbot.BRAKE)


print(f"starting in zone {sbot.comp.zone}", flush=True)
sbot.leds.set_colour(0, Colour.GREEN)
start = time.monotonic()
seen_any = False
steps = 0
while time.monotonic() - start < 3 and steps < 20:
    steps += 1
    markers = sbot.vision.detect_markers()
    arena = [m for m in markers if m.id < 28]
    if arena:
        seen_any = True
        nearest = min(arena, key=lambda m: m.position.distance)
        angle = nearest.position.horizontal_angle
        turn = max(-0.3, min(0.3, angle))
        drive(0.4 + turn, 0.4 - turn)
        if nearest.position.distance < 500:
            stop()
            sbot.servos.set_position(GRABBER, 1)
            sbot.utils.sound_buzzer(Note.C7, 0.2)
    else:
        drive(-0.2, 0.2)
    if sbot.arduino.digital_read(2) is False:
        stop()
    if sbot.arduino.measure_ultrasound_distance(TRIGGER, ECHO) in range(1, 150):
        drive(-0.3, -0.3)
    light = sbot.arduino.analog_read(AnalogPin.A0)
    assert 0 <= light <= 5
    assert not math.isnan(sbot.power.get_battery_data().voltage)
    sbot.utils.sleep(0.05)
stop()
sbot.servos.disable(GRABBER)
print("steps", steps, "saw markers", seen_any, "battery", sbot.power.get_battery_data().voltage)
