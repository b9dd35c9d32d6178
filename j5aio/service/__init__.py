"""The robot's service: astoria (Student Robotics, SourceBots) over MQTT (``j5aio[robot]``).

On a competition robot a management service runs the team's program from its USB stick,
reads the match's metadata from the competition's stick, offers a remote start on the
robot's web page, and shows the camera's frames there. It speaks MQTT through a
Mosquitto broker. This package is j5aio's client of it:

- :mod:`~j5aio.service.config`: where the broker is (``J5AIO_MQTT_URL``,
  ``SBOT_MQTT_URL``, ``astoria.toml``; ``J5AIO_SERVICE=off`` turns it off);
- :class:`~j5aio.service.service.RobotService` and
  :func:`~j5aio.service.auto.start_service`: the client's lifetime;
- :func:`~j5aio.service.service.publish_frame`: camera frames for the web page.

This package imports without the optional library ``aiomqtt``; starting the service
without it raises :class:`ServiceNotInstalledError`
(:func:`~j5aio.service.auto.start_service` logs it)
saying what to install. See "Running on the robot" in the documentation.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.service._extra import INSTALL_HINT, ServiceNotInstalledError
    from j5aio.service.auto import start_service
    from j5aio.service.config import ServiceConfig, ServiceConfigError, find_config
    from j5aio.service.service import RobotService, current_service, publish_frame

__all__ = [
    "INSTALL_HINT",
    "RobotService",
    "ServiceConfig",
    "ServiceConfigError",
    "ServiceNotInstalledError",
    "current_service",
    "find_config",
    "publish_frame",
    "start_service",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.service._extra": ["INSTALL_HINT", "ServiceNotInstalledError"],
            "j5aio.service.config": ["ServiceConfig", "ServiceConfigError", "find_config"],
            "j5aio.service.auto": ["start_service"],
            "j5aio.service.service": ["RobotService", "current_service", "publish_frame"],
        },
    )
