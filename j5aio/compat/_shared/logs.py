"""The peers' console logging: ``<logger> - <LEVEL> - <message>`` on stdout, and TRACE."""

from __future__ import annotations

import logging
import sys
from typing import Final

__all__ = ["TRACE", "add_trace_level", "setup_logging"]

#: The peers' level below DEBUG, at which the boards' wire traffic is logged.
TRACE: Final = 5


def add_trace_level() -> None:
    """Name level 5 ``TRACE`` in log lines."""
    logging.addLevelName(TRACE, "TRACE")


def setup_logging(debug_logging: bool, trace_logging: bool) -> None:
    """Log to stdout at INFO, or DEBUG / TRACE when asked for, as both peers do.

    The root logger gets a handler only if it has none yet (the program may have set up
    logging itself); the level is set in any case.
    """
    add_trace_level()
    root = logging.getLogger()
    if not root.handlers:
        handler = logging.StreamHandler(stream=sys.stdout)
        handler.setFormatter(logging.Formatter("%(name)s - %(levelname)s - %(message)s"))
        root.addHandler(handler)
    if trace_logging:
        root.setLevel(TRACE)
        logging.log(TRACE, "Trace Mode is enabled")
    elif debug_logging:
        root.setLevel(logging.DEBUG)
        logging.debug("Debug Mode is enabled")
    else:
        root.setLevel(logging.INFO)
