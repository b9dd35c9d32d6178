"""A status task that blinks the run LED and beeps, beside the robot's real work.

The status task never ends by itself: when the work is done, the program cancels it,
and its ``finally`` block turns the LED off on the way out. Run it with::

    python -m j5aio run --sim examples/async_status_lights.py
"""

from __future__ import annotations

import anyio

from j5aio.components.piezo import Note
from j5aio.kit import KitRobot

#: How long the LED stays on, then off, in seconds.
BLINK_INTERVAL = 0.2
#: Beep once every this many blinks.
BLINKS_PER_BEEP = 3


async def show_status(robot: KitRobot) -> None:
    """Blink the run LED and beep now and then, until cancelled; leave the LED off."""
    led = robot.power_board.run_led
    piezo = robot.power_board.piezo
    blinks = 0
    try:
        while True:
            await led.set_state(True)
            if blinks % BLINKS_PER_BEEP == 0:
                await piezo.buzz(0.05, Note.A6)
            await anyio.sleep(BLINK_INTERVAL)
            await led.set_state(False)
            await anyio.sleep(BLINK_INTERVAL)
            blinks += 1
    finally:
        with anyio.CancelScope(shield=True):  # the cleanup must not be cancelled too
            await led.set_state(False)


async def work(robot: KitRobot, seconds: float) -> None:
    """Stand-in for the robot's real job: turn slowly on the spot for ``seconds``."""
    left, right = robot.motor_boards[0].motors
    await left.set_power(0.3)
    await right.set_power(-0.3)
    await anyio.sleep(seconds)
    await left.set_power(0)
    await right.set_power(0)


async def main(seconds: float = 1.5) -> None:
    """Run the work with the status task beside it; stop the status task when work ends."""
    async with KitRobot() as robot:
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(show_status, robot)
            await work(robot, seconds)
            tasks.cancel_scope.cancel()  # the work is done: stop the status task
        led_on = await robot.power_board.run_led.get_state()
        print(f"Work done; the run LED is {'on' if led_on else 'off'}.")


if __name__ == "__main__":
    anyio.run(main)
