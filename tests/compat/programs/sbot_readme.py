"""The usage example of sbot's README (sbot 2026.1.0 on PyPI), as it is written there."""

# mypy: disable-error-code="import-not-found, name-defined"
# ruff: noqa: F403, F405
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

from sbot import *

motors.set_power(0, 0.3)
motors.set_power(1, 0.3)

power.get_output_current(PowerOutputPosition.H0)
utils.sound_buzzer(880, 0.5)

servos.set_position(0, 45/90)

print(arduino.measure_ultrasound_distance(8, 9))

if comp.is_competition:
    markers = vision.detect_markers()
    leds.set_colour(0, Colour.MAGENTA)
    print("markers", [marker.id for marker in markers])
