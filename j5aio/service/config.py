"""Where the robot's service is: finding the MQTT broker the way the competitions' APIs do.

:func:`find_config` looks, in this order, and the first that is there wins:

1. ``J5AIO_SERVICE=off`` (or ``0``, ``no``, ``false``): no service, whatever else is set;
2. ``J5AIO_MQTT_URL``: a URL in the form sbot reads (below), for j5aio only;
3. ``SBOT_MQTT_URL``: sbot's URL, read as sbot 2026 reads it;
4. ``astoria.toml`` in the working directory, then ``/etc/astoria.toml``: astoria's own
   configuration, as sr-robot3 reads it (its ``[mqtt]`` table: ``host``, ``port``,
   ``enable_tls``, ``topic_prefix``, ``force_protocol_version_3_1``).

A URL has the form ``mqtt[s]://[user[:password]@]host[:port][/topic_prefix]``:
``mqtts`` turns TLS on, the port defaults to 1883 (8883 with TLS) and the path, less its
leading ``/``, is the prefix of every topic.

With astoria's file the camera's frames go to ``camera/annotated`` with no prefix, as
sr-robot3 publishes them; with a URL they go to ``<prefix>/camera/annotated``, as sbot
publishes them.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Final

__all__ = [
    "ASTORIA_CONFIG_PATHS",
    "MQTT_URL_VARIABLE",
    "SBOT_MQTT_URL_VARIABLE",
    "SERVICE_VARIABLE",
    "ServiceConfig",
    "ServiceConfigError",
    "find_config",
    "parse_astoria_config",
    "parse_mqtt_url",
]

#: Set to ``off`` to run without the robot's service even where it is configured.
SERVICE_VARIABLE: Final = "J5AIO_SERVICE"
#: j5aio's own broker URL; it wins over sbot's and astoria's settings.
MQTT_URL_VARIABLE: Final = "J5AIO_MQTT_URL"
#: sbot's broker URL.
SBOT_MQTT_URL_VARIABLE: Final = "SBOT_MQTT_URL"
#: Where astoria's configuration is looked for, in order (as astoria and sr-robot3 do).
ASTORIA_CONFIG_PATHS: Final = (Path("astoria.toml"), Path("/etc/astoria.toml"))

_OFF: Final = frozenset({"off", "0", "no", "false", "disabled"})
_MAX_CONFIG_BYTES: Final = 64 * 1024


class ServiceConfigError(ValueError):
    """The service's configuration (a URL or ``astoria.toml``) is malformed."""


@dataclass(frozen=True)
class ServiceConfig:
    """How to reach the robot's service.

    :param host: the broker's host name or address.
    :param port: the broker's TCP port (1 to 65535).
    :param topic_prefix: put before every topic the service uses (``"astoria"`` on SR's
        robots); empty for none.
    :param tls: connect with TLS.
    :param mqtt_v311: speak MQTT 3.1.1 rather than 5 (astoria's
        ``force_protocol_version_3_1``).
    :param username: the broker's user name, or ``None``.
    :param password: the broker's password, or ``None``.
    :param frame_topic: where annotated camera frames are published (the whole topic).
    :param source: where this came from, for messages (a file or a variable's name).
    :raises ServiceConfigError: a field is out of range.
    """

    host: str
    port: int = 1883
    topic_prefix: str = "astoria"
    tls: bool = False
    mqtt_v311: bool = False
    username: str | None = None
    password: str | None = field(default=None, repr=False)
    frame_topic: str = "camera/annotated"
    source: str = "defaults"

    def __post_init__(self) -> None:
        if not isinstance(self.host, str) or not self.host:
            raise ServiceConfigError(f"{self.source}: the broker's host must be a name")
        if isinstance(self.port, bool) or not isinstance(self.port, int) or not (
            1 <= self.port <= 65535
        ):
            raise ServiceConfigError(
                f"{self.source}: the broker's port must be a whole number from 1 to 65535, "
                f"not {self.port!r}"
            )
        for name in ("topic_prefix", "frame_topic"):
            value = getattr(self, name)
            if not isinstance(value, str) or any(c in value for c in "+#\0"):
                raise ServiceConfigError(
                    f"{self.source}: {name} must be text without '+', '#' or NUL, "
                    f"not {value!r}"
                )

    def topic(self, name: str) -> str:
        """The whole topic for ``name`` under this configuration's prefix."""
        return f"{self.topic_prefix}/{name}" if self.topic_prefix else name


def parse_mqtt_url(url: str, source: str = MQTT_URL_VARIABLE) -> ServiceConfig:
    """Read a broker URL, ``mqtt[s]://[user[:password]@]host[:port][/prefix]``, as sbot does.

    :param url: the URL.
    :param source: where it came from, for the error messages.
    :raises ServiceConfigError: the scheme is not ``mqtt`` or ``mqtts``, the host is
        missing, or the port is not a number from 1 to 65535.
    """
    from urllib.parse import urlsplit  # (here: most robots have no URL to read)

    parts = urlsplit(url, allow_fragments=False)
    if parts.scheme not in ("mqtt", "mqtts"):
        raise ServiceConfigError(
            f"{source}: the URL must start with mqtt:// or mqtts://, not {url!r}"
        )
    tls = parts.scheme == "mqtts"
    try:
        port = parts.port
    except ValueError:
        raise ServiceConfigError(
            f"{source}: the port in {url!r} must be a number from 1 to 65535"
        ) from None
    if not parts.hostname:
        raise ServiceConfigError(f"{source}: the URL {url!r} names no host")
    prefix = parts.path.lstrip("/")
    return ServiceConfig(
        host=parts.hostname,
        port=port or (8883 if tls else 1883),
        topic_prefix=prefix,
        tls=tls,
        username=parts.username,
        password=parts.password,
        frame_topic=f"{prefix}/camera/annotated" if prefix else "camera/annotated",
        source=source,
    )


def parse_astoria_config(data: Mapping[str, object], source: str) -> ServiceConfig:
    """Read the ``[mqtt]`` table of astoria's configuration (other tables are astoria's).

    :param data: the decoded TOML document.
    :param source: the file's path, for the error messages.
    :raises ServiceConfigError: the table is missing, has a key astoria does not know,
        or a value of the wrong type.
    """
    table = data.get("mqtt")
    if not isinstance(table, dict):
        raise ServiceConfigError(f"{source}: has no [mqtt] table (astoria needs one)")
    expected: dict[str, type] = {
        "host": str,
        "port": int,
        "enable_tls": bool,
        "topic_prefix": str,
        "force_protocol_version_3_1": bool,
    }
    unknown = sorted(set(table) - set(expected))
    if unknown:
        raise ServiceConfigError(
            f"{source}: [mqtt] has keys astoria does not know: {', '.join(unknown)} "
            f"(allowed: {', '.join(expected)})"
        )
    for key in ("host", "port"):
        if key not in table:
            raise ServiceConfigError(f"{source}: [mqtt] must give {key!r}")
    for key, kind in expected.items():
        value = table.get(key)
        if value is None:
            continue
        if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
            raise ServiceConfigError(
                f"{source}: [mqtt] {key} must be a {kind.__name__}, not {value!r}"
            )
    return ServiceConfig(
        host=table["host"],
        port=table["port"],
        topic_prefix=table.get("topic_prefix", "astoria"),
        tls=table.get("enable_tls", False),
        mqtt_v311=table.get("force_protocol_version_3_1", False),
        frame_topic="camera/annotated",
        source=source,
    )


def read_astoria_config(path: Path) -> ServiceConfig:
    """Read astoria's configuration file at ``path``.

    :raises ServiceConfigError: it cannot be read, is not TOML, or its ``[mqtt]`` is bad.
    """
    try:
        with path.open("rb") as file:
            raw = file.read(_MAX_CONFIG_BYTES + 1)
    except OSError as exc:
        raise ServiceConfigError(f"{path}: cannot be read: {exc.strerror or exc}") from None
    if len(raw) > _MAX_CONFIG_BYTES:
        raise ServiceConfigError(f"{path}: is larger than {_MAX_CONFIG_BYTES} bytes")
    import tomllib  # (here: only a robot with astoria's file reads TOML)

    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ServiceConfigError(f"{path}: is not valid TOML: {exc}") from None
    return parse_astoria_config(data, str(path))


def service_disabled(environ: Mapping[str, str] | None = None) -> bool:
    """Whether ``J5AIO_SERVICE`` says to run without the service."""
    env = os.environ if environ is None else environ
    return env.get(SERVICE_VARIABLE, "").strip().lower() in _OFF


def find_config(
    environ: Mapping[str, str] | None = None,
    search_paths: Sequence[Path] = ASTORIA_CONFIG_PATHS,
) -> ServiceConfig | None:
    """The service's configuration (see the module's documentation), or ``None``.

    :param environ: the environment to read; ``os.environ`` if omitted.
    :param search_paths: where to look for ``astoria.toml``, in order.
    :returns: ``None`` when the service is turned off or nothing configures it.
    :raises ServiceConfigError: the configuration that wins is malformed.
    """
    env = os.environ if environ is None else environ
    if service_disabled(env):
        return None
    for variable in (MQTT_URL_VARIABLE, SBOT_MQTT_URL_VARIABLE):
        url = env.get(variable)
        if url:
            return parse_mqtt_url(url, variable)
    for path in search_paths:
        if path.is_file():
            return read_astoria_config(path)
    return None
