"""sbot 2026.1.0, SourceBots' robot API, on j5aio.

A program written for sbot runs unchanged::

    from sbot import motors, servos, arduino, power, utils, comp

    motors.set_power(0, 0.5)   # motor 0 across the motor boards
    utils.sleep(1)
    print(comp.zone)

Run it with ``python -m j5aio run --api sbot robot.py`` (add ``--sim --kit sb2024`` for
the simulated kit), or import this package directly:
``from j5aio.compat.sbot import motors``.

As with sbot, taking the robot's modules (``from sbot import motors``) finds the boards
and waits for the start button, unless ``SBOT_SKIP_WAIT_START=1`` is set; then the
program calls ``utils.load_boards()`` and ``utils.wait_start()`` itself. sbot does this
as ``import sbot`` runs; here it happens when the first of ``motors``, ``servos``,
``power``, ``arduino``, ``leds``, ``vision``, ``utils`` or ``comp`` is taken from the
package, which for ``from sbot import ...`` is the same moment, and otherwise is before
the program's first use of the robot. So the package itself, its constants and its
submodules can be imported (by documentation, by tests) without a robot. With
``SBOT_PYTEST`` set, as in sbot, those eight names do not exist at all.
"""

from os import environ as _environ
from typing import TYPE_CHECKING, Any

from ._arduinos import AnalogPin, GPIOPinMode
from ._leds import Colour
from ._motors import MotorPower
from ._power import PowerOutputPosition
from ._utils import Note

if TYPE_CHECKING:
    from ._robot import arduino, comp, leds, motors, power, servos, utils, vision

_ROBOT_NAMES = frozenset(
    {"arduino", "comp", "leds", "motors", "power", "servos", "utils", "vision"},
)



def __getattr__(name: str) -> Any:
    """Give the robot's modules, finding the boards and waiting for the start first."""
    if name in _ROBOT_NAMES and "SBOT_PYTEST" not in _environ:
        from . import _robot

        return getattr(_robot, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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
