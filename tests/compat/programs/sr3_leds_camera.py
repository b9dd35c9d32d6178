"""An sr-robot3 program lighting the KCH's LEDs and looking at markers."""

import sys
from pathlib import Path

from sr.robot3 import LED_A, LED_C, Colour, Robot

robot = Robot()
robot.kch.leds[LED_A].colour = Colour.MAGENTA
robot.kch.leds[LED_C].r = True
robot.kch.leds[LED_C].g = True
robot.kch.leds[LED_C].b = False
print("leds", robot.kch.leds[LED_A].colour, robot.kch.leds[LED_C].colour)
print("channels", robot.kch.leds[LED_A].r, robot.kch.leds[LED_A].g, robot.kch.leds[LED_A].b)

markers = robot.camera.see()
print("markers", len(markers) > 0, all(m.position.distance > 0 for m in markers))
nearest = markers[0]
print("fields", type(nearest.id).__name__, type(nearest.size).__name__,
      type(nearest.position.distance).__name__, len(nearest.pixel_corners),
      nearest.pixel_centre.x > 0, isinstance(nearest.orientation.yaw, float))
folder = Path(sys.argv[1])
again = robot.camera.see(save=folder / "seen")
frame = robot.camera.capture(save=folder / "raw.png")
print("saved", (folder / "seen.jpg").is_file(), (folder / "raw.png").is_file(), frame.ndim)
print("from frame", [m.id for m in robot.camera.see(frame=frame)] == [m.id for m in again])
print("camera", robot.camera.identify().board_type, repr(robot.camera).startswith("<AprilCamera"))
