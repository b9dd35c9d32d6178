"""The robot's modules, made once, as ``import sbot`` makes them.

Importing this module finds the boards and waits for the start button, as sbot does,
unless the ``SKIP_WAIT_START`` override is set (``SBOT_SKIP_WAIT_START=1``): then a
program calls ``utils.load_boards()`` and ``utils.wait_start()`` itself.
"""

from __future__ import annotations

import logging

from ._arduinos import Arduino
from ._comp import Comp
from ._kit import KitLink
from ._leds import Led
from ._logging import setup_logging
from ._motors import Motor
from ._overrides import get_overrides, is_set
from ._power import Power
from ._servos import Servo
from ._utils import Utils
from ._version import __version__
from ._vision import Vision

__all__ = [
    "arduino",
    "boards",
    "comp",
    "leds",
    "motors",
    "overrides",
    "power",
    "servos",
    "utils",
    "vision",
]

logger = logging.getLogger("sbot.robot")

boards = KitLink()
power = Power(boards)
motors = Motor(boards)
servos = Servo(boards)
arduino = Arduino(boards)
vision = Vision(boards)
leds = Led(boards)
comp = Comp()
utils = Utils(boards, comp)

overrides = get_overrides()

setup_logging(
    debug_logging=is_set("ENABLE_DEBUG_LOGGING"),
    trace_logging=is_set("ENABLE_TRACE_LOGGING"),
)

logger.info("SourceBots API v%s (on j5aio)", __version__)

if not is_set("SKIP_WAIT_START"):
    utils.load_boards()
    utils.wait_start()
