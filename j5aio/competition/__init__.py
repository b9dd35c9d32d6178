"""Match day: metadata, the start, the match timer and run logs (for every kit).

- :mod:`j5aio.competition.metadata`: the match's arena, zone, mode and duration, from
  the robot service, ``J5AIO_METADATA``, ``SBOT_METADATA_PATH`` or a USB stick, in
  j5aio's, astoria's or sbot's format (else the development defaults);
- :mod:`j5aio.competition.start`: waiting for the start button, a runner's start file or
  a remote start;
- :mod:`j5aio.competition.service_state`: what the robot service has said (metadata,
  the team's stick), for the rest of this package;
- :mod:`j5aio.competition.timer`: the watchdog that ends a match with every board safe;
- :mod:`j5aio.competition.clock`: robot time, scaled on a simulated kit;
- :mod:`j5aio.competition.runlog`: ``python -m j5aio run``'s log files.

A robot uses them through :meth:`~j5aio.robot.BaseRobot.wait_start` (or
``wait_for_start=True``, or, in a match, the watch
:meth:`~j5aio.robot.BaseRobot.watch_for_start` starts on entry) and its ``arena`` /
``zone`` / ``mode`` / ``is_competition`` / ``usb_stick`` properties.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.competition.clock import MatchClock as MatchClock
    from j5aio.competition.metadata import Metadata as Metadata
    from j5aio.competition.metadata import MetadataError as MetadataError
    from j5aio.competition.metadata import Mode as Mode
    from j5aio.competition.metadata import load_metadata as load_metadata
    from j5aio.competition.start import start_file as start_file
    from j5aio.competition.start import trigger_start as trigger_start
    from j5aio.competition.timer import MatchTimer as MatchTimer
    from j5aio.competition.timer import add_game_over_hook as add_game_over_hook

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.competition.clock": ["MatchClock"],
            "j5aio.competition.metadata": ["Metadata", "MetadataError", "Mode", "load_metadata"],
            "j5aio.competition.start": ["start_file", "trigger_start"],
            "j5aio.competition.timer": ["MatchTimer", "add_game_over_hook"],
        },
    )
