"""Drive to a token: the robot works out where it is, finds a token, and drives up to it.

Runs on the simulated kit, where the robot starts near the south wall facing north::

    J5AIO_ENV=sim python examples/drive_to_token.py

The tutorial "Where am I: drive to a token" in the documentation walks through it.
"""

import math

import anyio

from j5aio.kit import KitRobot
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.locate import CameraMount, marker_position
from j5aio.vision.track import PositionTracker

ARENA = ArenaMap.standard()  # the simulated arena; a team loads its own: ArenaMap.load(...)
MOUNT = CameraMount(forward=200)  # the camera is 200 mm in front of the robot's centre
SPEED_PER_POWER = 1240  # mm/s per unit of motor power (measured, see the tutorial)
TRACK_WIDTH = 300  # mm between the wheels
STOP_AT = 400  # mm between the robot's centre and the token's face


async def main() -> tuple[float, float]:
    """Drive to the first token seen; return where the program believes the token is."""
    target: tuple[float, float] | None = None
    async with KitRobot() as robot:
        camera = robot.camera
        if camera is None:
            raise SystemExit("This program needs a robot with a camera.")
        camera.set_marker_sizes(ARENA.marker_sizes())
        left, right = robot.motor_boards[0].motors[0], robot.motor_boards[0].motors[1]
        tracker = PositionTracker(camera, ARENA, MOUNT)

        async def drive(left_power: float, right_power: float) -> None:
            await left.set_power(left_power)
            await right.set_power(right_power)
            # Tell the tracker, so that it moves its estimate on between pictures.
            tracker.set_motion(
                (left_power + right_power) / 2 * SPEED_PER_POWER,
                (right_power - left_power) * SPEED_PER_POWER / TRACK_WIDTH,
            )

        # 1. Look around until the robot knows where it is and sees a token.
        with anyio.fail_after(30):
            while target is None:
                markers = await camera.see()
                where = tracker.observe(markers)
                tokens = [m for m in markers if m.id in ARENA.token_ids]
                if where is not None and tokens:
                    target = marker_position(tokens[0], where, MOUNT)  # the nearest
                    print(f"I am at {where}; token {tokens[0].id} is at "
                          f"({target[0]:.0f}, {target[1]:.0f}) mm")
                else:
                    await drive(-0.15, 0.15)  # turn left on the spot and look again
        # 2. Drive to it, steering by the estimate.
        with anyio.fail_after(30):
            while True:
                where = await tracker.update()
                assert where is not None  # there has been a fix: it carries on from it
                dx, dy = target[0] - where.x, target[1] - where.y
                if math.hypot(dx, dy) < STOP_AT:
                    break
                turn = math.remainder(math.atan2(dy, dx) - where.heading, math.tau)
                steer = max(-0.15, min(0.15, 0.5 * turn))
                forward = 0.4 if abs(turn) < 0.3 else 0.0
                await drive(forward - steer, forward + steer)
        await drive(0, 0)
        print(f"Stopped at {tracker.estimate()}")
    assert target is not None
    return target


if __name__ == "__main__":
    anyio.run(main)
