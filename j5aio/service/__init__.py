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
    from j5aio.service._extra import INSTALL_HINT as INSTALL_HINT
    from j5aio.service._extra import ServiceNotInstalledError as ServiceNotInstalledError
    from j5aio.service.auto import start_service as start_service
    from j5aio.service.config import ServiceConfig as ServiceConfig
    from j5aio.service.config import ServiceConfigError as ServiceConfigError
    from j5aio.service.config import find_config as find_config
    from j5aio.service.service import RobotService as RobotService
    from j5aio.service.service import current_service as current_service
    from j5aio.service.service import publish_frame as publish_frame

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.service._extra": ["INSTALL_HINT", "ServiceNotInstalledError"],
            "j5aio.service.config": ["ServiceConfig", "ServiceConfigError", "find_config"],
            "j5aio.service.auto": ["start_service"],
            "j5aio.service.service": ["RobotService", "current_service", "publish_frame"],
        },
    )
