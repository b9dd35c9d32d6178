"""sbot's logging set-up: lines ``<logger> - <LEVEL> - <message>`` on stdout."""

from __future__ import annotations

import logging
import sys

__all__ = ["TRACE", "setup_logging"]

#: The level below DEBUG that sbot logs wire traffic at.
TRACE = 5


def setup_logging(debug_logging: bool, trace_logging: bool) -> None:
    """Log to stdout at INFO (DEBUG, TRACE if asked), unless the program set up logging.

    The root logger gets a handler only if it has none, as sbot does; the level is
    set in any case.
    """
    logging.addLevelName(TRACE, "TRACE")
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
