"""A student's program for a Bee Board robot: the sync facade, as for j5aio's own boards.

It names no backend, so the same program runs on the boards plugged in
(``python -m j5aio run bee_robot.py``), on the simulated kit
(``python -m j5aio run --sim --kit bee bee_robot.py``) and on the console
(``J5AIO_ENV=console python bee_robot.py``).
"""

from __future__ import annotations

from beekit.sync import BeeBoard

from j5aio.sync import Environment, get_default_environment


def main(environment: Environment | None = None) -> BeeBoard:
    """Light the LED, wait for the button, then drive forward at half power.

    :param environment: where the board is; the one ``J5AIO_ENV`` chooses by default.
    """
    where = environment or get_default_environment()
    bee = where.get_board_group(BeeBoard).singular()
    bee.led.state = True
    bee.button.wait_until_pressed()
    bee.motors[0].power = 0.5
    bee.motors[1].power = 0.5
    return bee


if __name__ == "__main__":
    main()
