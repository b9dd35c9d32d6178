"""Derived components: components built out of other components.

``UltrasoundSensor`` and ``UltrasoundInterface`` are importable from here, as in j5.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.components.derived.ultrasound import UltrasoundInterface as UltrasoundInterface
    from j5aio.components.derived.ultrasound import UltrasoundSensor as UltrasoundSensor

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.components.derived.ultrasound": ["UltrasoundInterface", "UltrasoundSensor"],
        },
    )
