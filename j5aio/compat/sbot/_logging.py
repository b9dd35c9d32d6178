"""sbot's logging set-up: lines ``<logger> - <LEVEL> - <message>`` on stdout.

sr-robot3 logs the same way: both take it from ``j5aio.compat._shared.logs``.
"""

from __future__ import annotations

from j5aio.compat._shared.logs import TRACE, setup_logging

__all__ = ["TRACE", "setup_logging"]
