"""The TRACE log level and the wire loggers.

Every byte that crosses a transport is logged at :data:`TRACE` (numeric 5, below
``DEBUG``) on the logger ``j5aio.wire.<port>``, in both directions. To watch the traffic
of one board::

    import logging
    from j5aio.backends.hardware.transports import TRACE

    logging.basicConfig(level=TRACE)
    # or only one port:
    logging.getLogger("j5aio.wire./dev/ttyACM0").setLevel(TRACE)

Dots in a port name are replaced by underscores, so that a URL such as
``socket://127.0.0.1:9000`` names one logger instead of a hierarchy.
"""

from __future__ import annotations

import logging

__all__ = ["TRACE", "WIRE_LOGGER_PREFIX", "log_wire", "wire_logger"]

#: The numeric level of TRACE, the level of wire traffic (below ``logging.DEBUG``).
TRACE = 5

#: The prefix of every wire logger's name.
WIRE_LOGGER_PREFIX = "j5aio.wire"

logging.addLevelName(TRACE, "TRACE")


def wire_logger(port: str) -> logging.Logger:
    """Return the logger that records the traffic of ``port``."""
    return logging.getLogger(f"{WIRE_LOGGER_PREFIX}.{port.replace('.', '_')}")


def log_wire(logger: logging.Logger, direction: str, data: bytes) -> None:
    """Log ``data`` crossing the wire in ``direction`` (``"->"`` sent, ``"<-"`` received).

    Cheap when TRACE is disabled: the message is only formatted when it will be emitted.
    """
    if logger.isEnabledFor(TRACE):
        logger.log(TRACE, "%s %r", direction, data)
