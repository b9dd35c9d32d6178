"""sbot 2026.1.0, SourceBots' robot API, on j5aio.

A program written for sbot runs unchanged::

    from sbot import motors, servos, arduino, power, utils, comp

    motors.set_power(0, 0.5)   # motor 0 across the motor boards
    utils.sleep(1)
    print(comp.zone)

Run it with ``python -m j5aio run --api sbot robot.py`` (add ``--sim --kit sb2024`` for
the simulated kit), or import this package directly:
``from j5aio.compat.sbot import motors``.

As with sbot, importing the modules (``motors``, ``utils``...) finds the boards and waits
for the start button, unless ``SBOT_SKIP_WAIT_START=1`` is set. With ``SBOT_PYTEST`` set
only the enums and constants are imported, and no board is looked for.
"""

from os import environ as _environ

from ._arduinos import AnalogPin, GPIOPinMode
from ._leds import Colour
from ._motors import MotorPower
from ._power import PowerOutputPosition
from ._utils import Note

if "SBOT_PYTEST" not in _environ:
    from .robot import arduino, comp, leds, motors, power, servos, utils, vision

BRAKE = MotorPower.BRAKE
COAST = MotorPower.COAST

__all__ = [
    "BRAKE",
    "COAST",
    "AnalogPin",
    "Colour",
    "GPIOPinMode",
    "MotorPower",
    "Note",
    "PowerOutputPosition",
    "arduino",
    "comp",
    "leds",
    "motors",
    "power",
    "servos",
    "utils",
    "vision",
]
