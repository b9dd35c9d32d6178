"""What the generator wraps: a :class:`Scope` of modules, and j5aio's own (:data:`CORE_SCOPE`)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "CORE_FAMILIES",
    "CORE_OUTPUT",
    "CORE_PACKAGE",
    "CORE_SCOPE",
    "FORWARDED_DUNDERS",
    "LINE_LENGTH",
    "Scope",
    "core_family",
]

#: The package j5aio's own facade is written as: an index (its ``__init__``) and one module
#: per family of classes.
CORE_PACKAGE = "j5aio.sync._generated"

#: Where j5aio's own facade is written: the folder of :data:`CORE_PACKAGE`.
CORE_OUTPUT = Path(__file__).resolve().parent.parent / "sync" / "_generated"

#: The family (the facade's module) of the classes of each core module: the first entry
#: whose module (or package) holds the class's module; every other class is in
#: ``"robot"``, with the robots, boards and components in general. A program imports the
#: families of what it uses: a robot that finds its boards needs ``"robot"`` alone, and
#: one that drives the motors of an SR kit ``"sr"`` and ``"components"`` besides. Each
#: module imported costs some 0.1 ms besides its classes, so a family is a few modules
#: that programs use together, not one each.
CORE_FAMILIES: tuple[tuple[str, str], ...] = (
    ("j5aio.boards.sr", "sr"),
    ("j5aio.boards.sb", "sb"),
    ("j5aio.boards.arduino", "arduino"),
    ("j5aio.boards.camera", "vision"),
    ("j5aio.vision", "vision"),
    ("j5aio.components.marker_camera", "vision"),
    ("j5aio.backends", "environment"),
    ("j5aio.environments", "environment"),
    ("j5aio.components.component", "robot"),
    ("j5aio.components.identified", "robot"),
    # the components of firmware 4's boards and of the KCH, beside those of every kit
    ("j5aio.components.monitored_motor", "fw4"),
    ("j5aio.components.protected_power_output", "fw4"),
    ("j5aio.components.pulse_servo", "fw4"),
    ("j5aio.components.fan", "fw4"),
    ("j5aio.components.flag", "fw4"),
    ("j5aio.components.flashing_led", "fw4"),
    ("j5aio.components.rgb_led", "fw4"),
    ("j5aio.components.supply_sensor", "fw4"),
    ("j5aio.components.temperature_sensor", "fw4"),
    ("j5aio.components.voltage_sensor", "fw4"),
    ("j5aio.components", "components"),
)


def core_family(module: str) -> str:
    """The family of the classes defined in ``module``: the facade's module that wraps them.

    Each family is a module of j5aio's facade: ``"sr"`` for Student Robotics' boards,
    ``"sb"`` for SourceBots', ``"arduino"``, ``"vision"`` (the camera board, its marker
    camera, the position tracker), ``"environment"``, ``"components"`` (those of every
    kit), ``"fw4"`` (those of firmware 4's boards and the KCH), and ``"robot"`` for the
    rest (the robots, and boards and components in general).
    """
    for prefix, family in CORE_FAMILIES:
        if module == prefix or module.startswith(prefix + "."):
            return family
    return "robot"

#: Dunder methods forwarded when a core class defines them.
FORWARDED_DUNDERS = ("__getitem__", "__iter__", "__len__", "__contains__", "__bool__", "__call__")

LINE_LENGTH = 100

_NONE_TYPE = type(None)


@dataclass(frozen=True)
class Scope:
    """What to wrap: the modules to read and the extras j5aio's own facade needs.

    :param modules: modules (or packages, walked) whose classes are wrapped.
    :param extra_classes: further ``(module, class name)`` pairs to wrap.
    :param environment_packages: packages searched for module-level environment objects.
    :param function_modules: modules whose public functions are wrapped when they take or
        return wrapped objects.
    :param skipped_packages: packages never imported while walking.
    """

    modules: tuple[str, ...]
    extra_classes: tuple[tuple[str, str], ...] = ()
    environment_packages: tuple[str, ...] = ()
    function_modules: tuple[str, ...] = ()
    skipped_packages: tuple[str, ...] = ()

    @property
    def is_core(self) -> bool:
        """Whether this is j5aio's own facade (which wraps no other facade's classes)."""
        return self == CORE_SCOPE


#: j5aio's own facade, the package ``j5aio/sync/_generated``.
CORE_SCOPE = Scope(
    modules=("j5aio.components", "j5aio.boards"),
    extra_classes=(
        ("j5aio.backends.environment", "Environment"),
        ("j5aio.robot", "BaseRobot"),
        ("j5aio.kit", "KitRobot"),
        ("j5aio.vision.track", "PositionTracker"),
    ),
    environment_packages=("j5aio.backends",),
    function_modules=("j5aio.environments",),
    skipped_packages=("j5aio.sync",),
)
