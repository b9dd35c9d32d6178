"""Drive to a token, in plain (sync) code: as examples/drive_to_token.py, without await.

    J5AIO_ENV=sim python examples/sync_drive_to_token.py
"""

import math

from j5aio.sync import KitRobot, PositionTracker
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.locate import CameraMount, marker_position

ARENA = ArenaMap.standard()
MOUNT = CameraMount(forward=200)
SPEED_PER_POWER = 1240  # mm/s per unit of motor power
TRACK_WIDTH = 300  # mm
STOP_AT = 400  # mm

robot = KitRobot()
camera = robot.camera
if camera is None:
    raise SystemExit("This program needs a robot with a camera.")
camera.set_marker_sizes(ARENA.marker_sizes())
left, right = robot.motor_boards[0].motors[0], robot.motor_boards[0].motors[1]
tracker = PositionTracker(camera, ARENA, MOUNT)


def drive(left_power: float, right_power: float) -> None:
    left.power, right.power = left_power, right_power
    tracker.set_motion(
        (left_power + right_power) / 2 * SPEED_PER_POWER,
        (right_power - left_power) * SPEED_PER_POWER / TRACK_WIDTH,
    )


target = None
while target is None:
    markers = camera.see()
    where = tracker.observe(markers)
    tokens = [m for m in markers if m.id in ARENA.token_ids]
    if where is not None and tokens:
        target = marker_position(tokens[0], where, MOUNT)
        print(f"Token {tokens[0].id} is at ({target[0]:.0f}, {target[1]:.0f}) mm")
    else:
        drive(-0.15, 0.15)

while True:
    where = tracker.update()
    assert where is not None  # there has been a fix: the estimate carries on from it
    dx, dy = target[0] - where.x, target[1] - where.y
    if math.hypot(dx, dy) < STOP_AT:
        break
    turn = math.remainder(math.atan2(dy, dx) - where.heading, math.tau)
    steer = max(-0.15, min(0.15, 0.5 * turn))
    forward = 0.4 if abs(turn) < 0.3 else 0.0
    drive(forward - steer, forward + steer)
drive(0, 0)
print(f"Stopped at {tracker.estimate()}")
