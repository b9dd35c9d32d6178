"""Three behaviours at once, on the console: drive, blink an LED, watch the battery.

Run it and answer the battery prompts (or pipe answers in)::

    printf '12.1\n11.8\n10.2\n' | python examples/async_console_robot.py

While the battery task waits for your answer, the drive and blink tasks carry on: their
lines appear between the prompt and your reply.
"""

from __future__ import annotations

import anyio

from j5aio import BaseRobot, BoardGroup
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
)
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.components.motor import MotorSpecialState

LOW_BATTERY_VOLTS = 10.5


class ConsoleRobot(BaseRobot):
    """A robot with one power board and one motor board, both on the console."""

    power_board: PowerBoard
    motor_board: MotorBoard

    async def setup(self) -> None:
        """Find the two boards."""
        powers = await BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend)
        self.power_board = powers.singular()
        motors = await BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)
        self.motor_board = motors.singular()


async def drive(robot: ConsoleRobot, legs: int) -> None:
    """Drive forwards and turn, ``legs`` times, then brake."""
    left, right = robot.motor_board.motors
    for _ in range(legs):
        await left.set_power(0.6)
        await right.set_power(0.6)
        await anyio.sleep(0.3)
        await left.set_power(-0.4)
        await anyio.sleep(0.2)
    await left.set_power(MotorSpecialState.BRAKE)
    await right.set_power(MotorSpecialState.BRAKE)


async def blink(robot: ConsoleRobot, flashes: int) -> None:
    """Flash the run LED ``flashes`` times."""
    for _ in range(flashes):
        await robot.power_board.run_led.set_state(True)
        await anyio.sleep(0.1)
        await robot.power_board.run_led.set_state(False)
        await anyio.sleep(0.1)


async def watch_battery(robot: ConsoleRobot, readings: int) -> None:
    """Read the battery ``readings`` times and sound the piezo if it runs low."""
    for _ in range(readings):
        volts = await robot.power_board.battery_sensor.get_voltage()
        print(f"battery: {volts:.1f} V")
        if volts < LOW_BATTERY_VOLTS:
            print("battery low: charge it soon")
            await robot.power_board.piezo.buzz(0.2, 440)
        await anyio.sleep(0.2)


async def main() -> None:
    """Run the three behaviours side by side; every board is made safe at the end."""
    async with ConsoleRobot() as robot, anyio.create_task_group() as tasks:
        tasks.start_soon(drive, robot, 3)
        tasks.start_soon(blink, robot, 6)
        tasks.start_soon(watch_battery, robot, 3)


if __name__ == "__main__":
    anyio.run(main)
