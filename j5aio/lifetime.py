"""The safety net's former home; everything is in :mod:`j5aio.safety` now.

Kept so that code written against it keeps working: it exports what
:mod:`j5aio.safety`'s modules of the registry, the rescue and the process hooks export
(the names are theirs, and so are the lists of them).
"""

from __future__ import annotations

from j5aio.safety import hooks, registry, rescue
from j5aio.safety.hooks import *  # noqa: F403
from j5aio.safety.registry import *  # noqa: F403
from j5aio.safety.rescue import *  # noqa: F403

__all__: list[str] = []
__all__ += hooks.__all__
__all__ += registry.__all__
__all__ += rescue.__all__
