"""Starting the robot's service client where the service is configured, and only there.

Finding out that no service is configured costs a look at a few environment variables
and two paths (:func:`~j5aio.competition.service_state.service_may_be_configured`, which
a robot asks before it imports this package), and nothing more is imported (not even the
reader of the configuration, :mod:`j5aio.service.config`).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import TYPE_CHECKING, Final

from j5aio.competition.service_state import service_may_be_configured

if TYPE_CHECKING:
    from j5aio.service.config import ServiceConfig
    from j5aio.service.service import RobotService

__all__ = ["SETTLE_TIMEOUT", "start_service"]

LOGGER = logging.getLogger(__name__)

#: Seconds :func:`start_service` waits at most for what the service said before (a
#: broker that does not answer at once costs no more than this).
SETTLE_TIMEOUT: Final = 0.5
#: Frames a second sent at most, unless told otherwise (as
#: :data:`j5aio.service.frames.DEFAULT_MAX_RATE`).
_DEFAULT_MAX_RATE: Final = 5.0


async def start_service(
    config: ServiceConfig | None = None,
    *,
    environ: Mapping[str, str] | None = None,
    max_frame_rate: float = _DEFAULT_MAX_RATE,
    settle: float = SETTLE_TIMEOUT,
) -> RobotService | None:
    """Start the robot's service client if the service is configured; returns at once.

    With no ``config``, the environment decides
    (:func:`~j5aio.service.config.find_config`): on where ``astoria.toml``,
    ``SBOT_MQTT_URL`` or ``J5AIO_MQTT_URL`` says where the broker is, off where nothing
    does or ``J5AIO_SERVICE=off``. A configuration that cannot be read, or a missing
    aiomqtt, is logged as an error and the robot runs without the service (a match
    must not be lost to it).

    :param config: where the broker is; found from the environment if omitted.
    :param environ: the environment to read (``os.environ`` if omitted).
    :param max_frame_rate: camera frames a second sent at most.
    :param settle: wait at most this many seconds for the service's retained messages
        (:meth:`~j5aio.service.service.RobotService.wait_settled`), so that a program
        reading its zone before the start already has the service's; an absent broker
        is not waited for.
    :returns: the running service, or ``None`` when there is none.
    """
    if config is None:
        if not service_may_be_configured(environ):
            LOGGER.debug("Robot service: not configured here")
            return None
        from j5aio.service.config import ServiceConfigError, find_config

        try:
            config = find_config(environ)
        except ServiceConfigError as exc:
            LOGGER.error("Robot service: not started, its configuration is bad: %s", exc)
            return None
        if config is None:
            LOGGER.debug("Robot service: not configured here")
            return None
    from j5aio.service._extra import ServiceNotInstalledError
    from j5aio.service.service import RobotService

    try:
        service = RobotService(config, max_frame_rate=max_frame_rate)
    except ServiceNotInstalledError as exc:
        LOGGER.error("Robot service: not started: %s", exc)
        return None
    await service.start()
    LOGGER.info(
        "Robot service: talking to the broker at %s:%s (from %s)",
        config.host, config.port, config.source,
    )
    await service.wait_settled(settle)
    return service
