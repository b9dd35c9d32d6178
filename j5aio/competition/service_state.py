"""What the robot's management service has told this program, for the competition layer.

On a competition robot a service (astoria, over MQTT: ``j5aio.service``) knows the
match's metadata and where the team's USB stick is mounted. The service client writes
what it hears here; the competition layer (:mod:`j5aio.competition.metadata`, the run
log, :class:`~j5aio.robot.BaseRobot`) reads it. Neither imports the other, so the
competition layer works the same with the service, without it, and without the optional
MQTT extra installed.

Every function is safe to call from any thread. Listeners are called on the thread that
made the change, after it is made; a listener that raises is logged and skipped.
"""

from __future__ import annotations

import logging
import os
import threading
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Final

if TYPE_CHECKING:
    from j5aio.competition.metadata import Metadata

__all__ = [
    "add_listener",
    "clear",
    "metadata",
    "remove_listener",
    "service_may_be_configured",
    "set_metadata",
    "set_usercode_path",
    "usercode_path",
]

LOGGER = logging.getLogger(__name__)

_lock = threading.Lock()
_metadata: Metadata | None = None
_usercode_path: Path | None = None
_listeners: list[Callable[[], None]] = []


def metadata() -> Metadata | None:
    """The match metadata the service last sent, or ``None`` if it has sent none."""
    return _metadata


def usercode_path() -> Path | None:
    """Where the service says the team's code (its USB stick) is mounted, or ``None``."""
    return _usercode_path


def set_metadata(value: Metadata | None) -> None:
    """Record the service's metadata (``None``: forget it), then tell the listeners."""
    _record("_metadata", value)


def set_usercode_path(value: Path | None) -> None:
    """Record where the team's USB stick is (``None``: forget it), then tell the listeners."""
    _record("_usercode_path", value)


def _record(name: str, value: object) -> None:
    """Set this module's global ``name`` to ``value``; tell the listeners if it changed."""
    state = globals()
    with _lock:
        changed = value != state[name]
        state[name] = value
    if changed:
        _notify()


def add_listener(listener: Callable[[], None]) -> None:
    """Call ``listener()`` after each change to the metadata or the stick's path."""
    with _lock:
        if listener not in _listeners:
            _listeners.append(listener)


def remove_listener(listener: Callable[[], None]) -> None:
    """Stop calling ``listener`` (nothing happens if it was not added)."""
    with _lock:
        if listener in _listeners:
            _listeners.remove(listener)


def clear() -> None:
    """Forget everything the service said and every listener (for tests, and at exit)."""
    global _metadata, _usercode_path
    with _lock:
        _metadata = None
        _usercode_path = None
        _listeners.clear()


def _notify() -> None:
    with _lock:
        listeners = list(_listeners)
    for listener in listeners:
        try:
            listener()
        except Exception:
            LOGGER.exception("A listener of the robot service's state failed")


# What configures the service, for a quick look that reads nothing: the variables and
# files :func:`j5aio.service.config.find_config` reads (named as there; a test checks
# that they agree).
_SERVICE_VARIABLE: Final = "J5AIO_SERVICE"
_URL_VARIABLES: Final = ("J5AIO_MQTT_URL", "SBOT_MQTT_URL")
_CONFIG_PATHS: Final = ("astoria.toml", "/etc/astoria.toml")
_OFF: Final = frozenset({"off", "0", "no", "false", "disabled"})


def service_may_be_configured(environ: Mapping[str, str] | None = None) -> bool:
    """Whether the robot service may be configured here: False only where it surely is not.

    It looks at a few environment variables and for astoria's two configuration files,
    and imports nothing: a robot where nothing configures the service (or
    ``J5AIO_SERVICE=off`` turns it off) loads none of :mod:`j5aio.service`.
    :func:`j5aio.service.config.find_config` decides where this says it may be.

    :param environ: the environment to read (``os.environ`` if omitted).
    """
    environ = os.environ if environ is None else environ
    if environ.get(_SERVICE_VARIABLE, "").strip().lower() in _OFF:
        return False
    if any(environ.get(variable) for variable in _URL_VARIABLES):
        return True
    return any(os.path.isfile(path) for path in _CONFIG_PATHS)
