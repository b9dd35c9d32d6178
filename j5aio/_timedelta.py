"""``datetime.timedelta``, without running the source of :mod:`datetime`.

j5aio needs one thing of :mod:`datetime` on a start: the class ``timedelta``, for the
piezo's durations and the ultrasound's pulses. CPython's ``datetime`` module is a large
pure-Python module (about 100 KiB of code, most of a millisecond to import) whose last
act is to replace its classes with those of the C module ``_datetime``; importing the
class from there directly gives the very same class, ``datetime.timedelta``, for a
fraction of the time and memory. Where there is no ``_datetime`` (another Python), the
class comes from :mod:`datetime` as usual.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

__all__ = ["timedelta"]

if TYPE_CHECKING:
    from datetime import timedelta
else:
    try:
        from _datetime import timedelta
    except ImportError:  # a Python without CPython's C module: the same class, made here
        from datetime import timedelta
