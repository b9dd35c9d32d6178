"""Derived components: components built out of other components.

``UltrasoundSensor`` and ``UltrasoundInterface`` are importable from here, as in j5.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor

__all__ = ["UltrasoundInterface", "UltrasoundSensor"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.components.derived.ultrasound": ["UltrasoundInterface", "UltrasoundSensor"],
        },
    )
