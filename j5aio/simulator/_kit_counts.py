"""The counts of a simulated kit's boards and its time scale: their checks.

Both :class:`~j5aio.simulator.kit.SimulatedKit` (which every program on the simulated kit
makes) and :class:`~j5aio.simulator.kit.KitConfig` (which only a kit made from counts
needs) check them, so they live here, below both.
"""

from __future__ import annotations

from typing import Final

__all__ = ["CONFIG_SIMULATORS", "MAX_BOARDS_OF_A_KIND", "check_count", "check_time_scale"]

#: The most boards of one kind a simulated kit may have (documented as
#: :data:`j5aio.simulator.kit.MAX_BOARDS_OF_A_KIND`).
MAX_BOARDS_OF_A_KIND: Final = 99

#: The simulator (by registry name) each count of a
#: :class:`~j5aio.simulator.kit.KitConfig` makes.
CONFIG_SIMULATORS: Final = {
    "power_boards": "sr-power",
    "motor_boards": "sr-motor",
    "servo_boards": "sr-servo",
    "sb_arduinos": "sb-arduino",
    "ruggeduinos": "sr-ruggeduino",
}


def check_time_scale(value: object) -> None:
    """Check a kit's time scale: a number, 0 or more.

    :raises TypeError: it is not a number.
    :raises ValueError: it is negative (or NaN).
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"time_scale must be a number, not {type(value).__name__}")
    if not value >= 0:
        raise ValueError(f"time_scale must be 0 or more, not {value}")


def check_count(name: str, value: object) -> None:
    """Check how many boards of ``name`` a kit has: a whole number from 0 to 99.

    :raises TypeError: it is not an int.
    :raises ValueError: it is outside 0 to 99.
    """
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{name} must be an int, not {type(value).__name__}")
    if not 0 <= value <= MAX_BOARDS_OF_A_KIND:
        raise ValueError(f"{name} must be between 0 and {MAX_BOARDS_OF_A_KIND}, not {value}")
