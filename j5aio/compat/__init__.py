"""The competitions' own APIs, as thin layers on j5aio's core.

- ``j5aio.compat.sr_robot3``: Student Robotics' ``sr.robot3`` (sr-robot3 2026.0.3);
- ``j5aio.compat.sbot``: SourceBots' ``sbot``.

A team's program runs unchanged with ``python -m j5aio run --api sr-robot3 robot.py``
(or ``--api sbot``): ``import sr.robot3`` (``import sbot``) then gives these modules
(see ``j5aio.compat.imports``). They may also be imported directly:
``from j5aio.compat.sr_robot3 import *``.

Each is built on the sync facade (:mod:`j5aio.sync`), so its calls go through j5aio's
one runtime, components and boards; it only gives them the competition's names, units
and start-up.
"""

from __future__ import annotations

__all__: list[str] = []
