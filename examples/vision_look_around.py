"""Look around: turn on the spot until a wall marker is straight ahead, then report it.

Runs on the simulated kit (it has a camera in a simulated arena) or on the console, where
you type what the camera sees::

    J5AIO_ENV=sim python examples/vision_look_around.py
    printf '5 2000 0\\n' | J5AIO_ENV=console python examples/vision_look_around.py
"""

import math
import time

from j5aio.boards.camera import CameraBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import get_default_environment

environment = get_default_environment()
camera = environment.get_board_group(CameraBoard)[0].camera
# The motor board takes its 12 V from the power board's outputs, off at power-up.
environment.get_board_group(PowerBoard)[0].outputs.power_on()
left, right = environment.get_board_group(MotorBoard)[0].motors
camera.set_marker_sizes({i: 150 for i in range(28)} | {i: 80 for i in range(100, 104)})

ahead = None
for _ in range(100):
    wall_markers = [m for m in camera.see() if m.id < 28]
    ahead = min(wall_markers, key=lambda m: abs(m.position.horizontal_angle), default=None)
    if ahead is not None and abs(math.degrees(ahead.position.horizontal_angle)) < 3:
        break
    left.power, right.power = 0.1, -0.1  # turn right a little, then look again
    time.sleep(0.1)
    left.power, right.power = 0, 0

left.power, right.power = 0, 0
if ahead is None:
    print("No wall marker in sight.")
else:
    print(f"Marker {ahead.id} is {ahead.position.distance / 1000:.2f} m straight ahead.")
