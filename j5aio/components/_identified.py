"""The old, private home of :mod:`j5aio.components.identified`, kept so that old imports work.

Import :class:`~j5aio.components.identified.IdentifiedComponent` and
:func:`~j5aio.components.identified.checked_backend` from
:mod:`j5aio.components.identified` (or :mod:`j5aio.components`) instead.
"""

from j5aio.components.identified import IdentifiedComponent, checked_backend

__all__ = ["IdentifiedComponent", "checked_backend"]
