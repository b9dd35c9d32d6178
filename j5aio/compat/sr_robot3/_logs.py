"""sr-robot3's console logging: ``<logger> - <LEVEL> - <message>`` on stdout, and TRACE.

sbot logs the same way: both take it from ``j5aio.compat._shared.logs``.
"""

from __future__ import annotations

from j5aio.compat._shared.logs import TRACE, add_trace_level, setup_logging

__all__ = ["TRACE", "add_trace_level", "setup_logging"]
