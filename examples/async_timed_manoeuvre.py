"""A manoeuvre of several tasks at once, with one time limit around all of them.

Turning on the spot until the ultrasound sensor sees a wall, while the flag servo waves:
two tasks in one task group, inside ``anyio.move_on_after``. When time runs out, the
scope cancels *both* tasks (each stops at its next ``await``), the program learns so
from ``scope.cancelled_caught``, and brakes. Run it with::

    python -m j5aio run --sim examples/async_timed_manoeuvre.py
"""

from __future__ import annotations

import anyio

from j5aio.components.motor import MotorSpecialState
from j5aio.kit import KitRobot

TRIGGER_PIN = 6
ECHO_PIN = 7
#: The manoeuvre gives up after this many seconds.
TIME_LIMIT = 1.5
#: A wall nearer than this, in metres, ends the turn.
WALL_DISTANCE = 0.5


async def turn_until_wall(robot: KitRobot, done: anyio.CancelScope) -> None:
    """Turn on the spot until the sensor sees a wall, then end the whole manoeuvre."""
    left, right = robot.motor_boards[0].motors
    sensor = robot.arduinos[0].ultrasound_sensors[TRIGGER_PIN, ECHO_PIN]
    await left.set_power(0.4)
    await right.set_power(-0.4)
    while True:
        distance = await sensor.distance()
        if distance is not None and distance < WALL_DISTANCE:
            done.cancel()  # found it: the flag can stop waving too
            return
        await anyio.sleep(0.05)


async def wave_flag(robot: KitRobot) -> None:
    """Wave the servo-board flag from side to side until cancelled."""
    flag = robot.servo_boards[0].servos[0]
    while True:
        for position in (-0.8, 0.8):
            await flag.set_position(position)
            await anyio.sleep(0.25)


async def manoeuvre(robot: KitRobot, time_limit: float = TIME_LIMIT) -> bool:
    """Turn towards a wall while waving; return whether the wall was found in time."""
    found = False
    with anyio.move_on_after(time_limit) as limit:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(turn_until_wall, robot, tasks.cancel_scope)
            tasks.start_soon(wave_flag, robot)
        found = True  # the task group ended before the time limit: the turn found the wall
    if limit.cancelled_caught:
        found = False
    for motor in robot.motor_boards[0].motors:
        await motor.set_power(MotorSpecialState.BRAKE)
    return found


async def main() -> None:
    """Try the manoeuvre once and say how it went."""
    async with KitRobot() as robot:
        if await manoeuvre(robot):
            print("Facing the wall: braked.")
        else:
            print(f"No wall within {TIME_LIMIT} s: gave up and braked.")


if __name__ == "__main__":
    anyio.run(main)
