"""Backends that drive real boards, and the hardware environment.

``HARDWARE_ENVIRONMENT`` (from :mod:`.env`) maps every supported board to its backend,
and ``await attach(port)`` (from :mod:`.identify`) identifies the serial board on a
port. They are loaded on first use, so importing the transports alone stays light.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from j5aio.errors import NotSupportedByHardwareError  # importable from here, as in j5

if TYPE_CHECKING:
    from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT
    from j5aio.backends.hardware.identify import attach

__all__ = ["HARDWARE_ENVIRONMENT", "NotSupportedByHardwareError", "attach"]


def __getattr__(name: str) -> Any:
    if name == "HARDWARE_ENVIRONMENT":
        from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT

        return HARDWARE_ENVIRONMENT
    if name == "attach":
        from j5aio.backends.hardware.identify import attach

        return attach
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
