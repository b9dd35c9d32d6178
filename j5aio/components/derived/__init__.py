"""Derived components: components built out of other components.

``UltrasoundSensor`` and ``UltrasoundInterface`` are importable from here, as in j5.
"""

from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor

__all__ = ["UltrasoundInterface", "UltrasoundSensor"]
