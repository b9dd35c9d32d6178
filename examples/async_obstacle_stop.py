"""Drive forwards until the ultrasound sensor sees something close, then brake.

The sensor is an HC-SR04 on the SourceBots Arduino: trigger on pin 6, echo on pin 7. Run
it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/async_obstacle_stop.py

Nothing stands in front of the simulated kit's sensor unless a test puts it there, so
on ``--sim`` the robot drives for its longest allowed time and then brakes.
"""

from __future__ import annotations

import anyio

from j5aio.components.motor import MotorSpecialState
from j5aio.kit import KitRobot

TRIGGER_PIN = 6
ECHO_PIN = 7
#: Brake when something is nearer than this, in metres.
STOP_DISTANCE = 0.3
#: Brake after this many seconds, whatever the sensor says.
LONGEST_DRIVE = 2.0
#: How often the sensor is read, in seconds.
READ_INTERVAL = 0.05


async def drive_until_obstacle(
    robot: KitRobot, *, stop_distance: float = STOP_DISTANCE, longest: float = LONGEST_DRIVE,
) -> float | None:
    """Drive forwards; return the distance that stopped the robot (``None``: time ran out).

    The motors are braked however this ends: by an obstacle, by running out of time, by
    an error, or by the task being cancelled (the brake is shielded from cancellation).
    """
    sensor = robot.arduinos[0].ultrasound_sensors[TRIGGER_PIN, ECHO_PIN]
    motors = robot.motor_boards[0].motors
    try:
        for motor in motors:
            await motor.set_power(0.5)
        with anyio.move_on_after(longest):
            while True:
                distance = await sensor.distance()
                if distance is not None and distance < stop_distance:
                    return distance
                await anyio.sleep(READ_INTERVAL)
        return None
    finally:
        with anyio.CancelScope(shield=True):
            for motor in motors:
                await motor.set_power(MotorSpecialState.BRAKE)


async def main() -> None:
    """Find the kit, drive until something is close, and say why the robot stopped."""
    async with KitRobot() as robot:
        distance = await drive_until_obstacle(robot)
        if distance is None:
            print(f"Nothing came within {STOP_DISTANCE} m in {LONGEST_DRIVE} s: braked.")
        else:
            print(f"Obstacle {distance:.2f} m ahead: braked.")


if __name__ == "__main__":
    anyio.run(main)
