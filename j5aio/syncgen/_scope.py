"""What the generator wraps: a :class:`Scope` of modules, and j5aio's own (:data:`CORE_SCOPE`)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["CORE_OUTPUT", "CORE_SCOPE", "FORWARDED_DUNDERS", "LINE_LENGTH", "Scope"]

#: Where j5aio's own facade is written.
CORE_OUTPUT = Path(__file__).resolve().parent.parent / "sync" / "_generated.py"

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


#: j5aio's own facade, ``j5aio/sync/_generated.py``.
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
