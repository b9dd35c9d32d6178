"""The optional MQTT library (``aiomqtt``), imported only when the service is started.

``import j5aio`` and ``import j5aio.service`` never import it: a robot without the
service runs without it, and one that needs it is told what to install.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Final

__all__ = ["INSTALL_HINT", "ServiceNotInstalledError", "require_aiomqtt"]

#: What to run to get the robot service's library.
INSTALL_HINT: Final = "pip install 'j5aio[robot]'"


class ServiceNotInstalledError(ImportError):
    """The robot's service was asked for, but its optional MQTT library is not installed."""


def require_aiomqtt() -> ModuleType:
    """Import and return ``aiomqtt``.

    :raises ~j5aio.service.ServiceNotInstalledError: it is not installed; the message
        says what to install.
    """
    try:
        return importlib.import_module("aiomqtt")
    except ImportError as exc:
        raise ServiceNotInstalledError(
            "Talking to the robot's service (astoria, over MQTT) needs the optional "
            f"library aiomqtt, which could not be imported ({exc}). Install it with: "
            f"{INSTALL_HINT}"
        ) from exc
