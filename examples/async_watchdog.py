"""A watchdog: brake the motors when the ultrasound sensor goes quiet.

One task drives, one reads the sensor and "feeds" the watchdog with every good reading,
and the watchdog brakes the motors (and stops the program) when no good reading came for
:data:`QUIET_AFTER` seconds: a sensor knocked loose must not leave the robot driving
blind. Run it with::

    python -m j5aio run --sim examples/async_watchdog.py

The simulated kit's sensor sees nothing unless a test places an object, so on ``--sim``
the watchdog bites soon after the start.
"""

from __future__ import annotations

import anyio

from j5aio.components.motor import MotorSpecialState
from j5aio.errors import CommunicationError
from j5aio.kit import KitRobot

TRIGGER_PIN = 6
ECHO_PIN = 7
#: Brake when the sensor has given no reading for this long, in seconds.
QUIET_AFTER = 0.5
#: How often the sensor is read, in seconds.
READ_INTERVAL = 0.05


class Watchdog:
    """Remembers when it was last fed; :meth:`wait_until_hungry` returns once it starves."""

    def __init__(self, quiet_after: float) -> None:
        self.quiet_after = quiet_after
        self.last_fed = anyio.current_time()

    def feed(self) -> None:
        """A good reading came: start the quiet period again."""
        self.last_fed = anyio.current_time()

    async def wait_until_hungry(self) -> float:
        """Return (with how long it went unfed) when nothing fed it for ``quiet_after`` s."""
        while True:
            quiet = anyio.current_time() - self.last_fed
            if quiet >= self.quiet_after:
                return quiet
            await anyio.sleep(self.quiet_after - quiet)


async def read_sensor(robot: KitRobot, watchdog: Watchdog) -> None:
    """Read the sensor for ever, feeding the watchdog with every reading that came back."""
    sensor = robot.arduinos[0].ultrasound_sensors[TRIGGER_PIN, ECHO_PIN]
    while True:
        try:
            distance = await sensor.distance()
        except CommunicationError:
            distance = None  # a board that does not answer is as quiet as a silent sensor
        if distance is not None:
            watchdog.feed()
        await anyio.sleep(READ_INTERVAL)


async def drive(robot: KitRobot) -> None:
    """Drive forwards slowly, for ever."""
    for motor in robot.motor_boards[0].motors:
        await motor.set_power(0.4)
    await anyio.sleep_forever()


async def guard(robot: KitRobot, quiet_after: float = QUIET_AFTER) -> float:
    """Drive while the sensor talks; brake once it falls quiet. Return how long it was quiet."""
    watchdog = Watchdog(quiet_after)
    async with anyio.create_task_group() as tasks:
        tasks.start_soon(read_sensor, robot, watchdog)
        tasks.start_soon(drive, robot)
        quiet = await watchdog.wait_until_hungry()
        tasks.cancel_scope.cancel()
    for motor in robot.motor_boards[0].motors:
        await motor.set_power(MotorSpecialState.BRAKE)
    return quiet


async def main() -> None:
    """Drive under the watchdog's eye."""
    async with KitRobot() as robot:
        quiet = await guard(robot)
        print(f"The sensor was quiet for {quiet:.2f} s: motors braked.")


if __name__ == "__main__":
    anyio.run(main)
