"""A student's program for a Bee Board robot: the sync facade, as for j5aio's own boards."""

from __future__ import annotations

from collections.abc import Sequence

from beekit.backend import BeeBackend
from beekit.sync import BeeBoard

from j5aio.sync import BoardGroup


def main(ports: Sequence[str] = ()) -> BeeBoard:
    """Light the LED, wait for the button, then drive forward at half power."""
    bee = BoardGroup.get_board_group(BeeBoard, BeeBackend, ports=ports).singular()
    bee.led.state = True
    bee.button.wait_until_pressed()
    bee.motors[0].power = 0.5
    bee.motors[1].power = 0.5
    return bee


if __name__ == "__main__":
    main()
