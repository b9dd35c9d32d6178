"""KitConfig: a simulated kit by how many of each seed-generation board it has.

Documented, and imported, as :class:`j5aio.simulator.kit.KitConfig`; it lives here so that
a program on a named kit (every ``run --sim``) does not make its class.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields

from ._kit_counts import CONFIG_SIMULATORS, check_count, check_time_scale

__all__ = ["KitConfig"]


@dataclass(frozen=True)
class KitConfig:
    """How many of each board the simulated kit has, and how fast its time runs.

    :param power_boards: SR v4 power boards (firmware 3, USB).
    :param motor_boards: SR v4 motor boards (firmware 3, serial).
    :param servo_boards: SR v4 servo boards (firmware 2, USB).
    :param sb_arduinos: SourceBots Arduinos (2019 firmware, serial).
    :param ruggeduinos: SR Ruggeduinos (firmware 1, serial).
    :param time_scale: multiplies the time a board takes to boot when its port opens (an
        Arduino's 1.5 s): ``1.0`` is as slow as the real boards, ``0`` (the default)
        instant. The boards' firmware timers (a note playing, an LED flashing) run on the
        kit's clock, at ``1 / time_scale`` of real time, or real time for ``0``.
    :raises TypeError: a count is not an int, or ``time_scale`` not a number.
    :raises ValueError: a count is outside 0 to 99, or ``time_scale`` is negative.
    """

    power_boards: int = 1
    motor_boards: int = 2
    servo_boards: int = 1
    sb_arduinos: int = 1
    ruggeduinos: int = 0
    time_scale: float = 0.0

    def __post_init__(self) -> None:
        for field in fields(self):
            value = getattr(self, field.name)
            if field.name == "time_scale":
                check_time_scale(value)
                continue
            check_count(field.name, value)

    def boards(self) -> dict[str, int]:
        """The simulators (by registry name) this configuration makes, and how many."""
        return {name: getattr(self, count) for count, name in CONFIG_SIMULATORS.items()}

    @classmethod
    def from_boards(cls, boards: Mapping[str, int], time_scale: float = 0.0) -> KitConfig:
        """The configuration with the seed-generation boards among ``boards``."""
        counts = {count: boards.get(name, 0) for count, name in CONFIG_SIMULATORS.items()}
        return cls(**counts, time_scale=time_scale)


# Documented, and imported, as j5aio.simulator.kit's (set once the dataclass is made).
KitConfig.__module__ = "j5aio.simulator.kit"
